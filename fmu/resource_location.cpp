#include "resource_location.h"

#include <cctype>

namespace rigidfmu {

namespace {

int hexDigit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

bool startsWith(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

// On Windows a file URI's path starts with its drive: file:///C:/dir is C:/dir (RFC 8089,
// appendix E.2), as fmpy and the FMI tools there write it.
#ifdef _WIN32
constexpr bool kDriveLetters = true;
#else
constexpr bool kDriveLetters = false;
#endif

bool isDrive(const std::string& p, size_t at) {
  return p.size() >= at + 2 && std::isalpha(static_cast<unsigned char>(p[at])) && p[at + 1] == ':';
}

}  // namespace

std::optional<std::string> resourceDirectory(const char* uri, std::string& why) {
  if (!uri || !*uri) {
    why = "no resource location was given";
    return std::nullopt;
  }
  std::string rest = uri;
  if (startsWith(rest, "file:")) {
    rest = rest.substr(5);
    if (startsWith(rest, "//") && !startsWith(rest, "///")) {
      // file://authority/path: only the local host is ours to read.
      rest = rest.substr(2);
      if (startsWith(rest, "localhost/")) {
        rest = rest.substr(9);
      } else {
        why = std::string("resource location \"") + uri + "\" names a remote host";
        return std::nullopt;
      }
    }
  }
  std::string path;
  for (size_t i = 0; i < rest.size(); ++i) {
    if (rest[i] == '%') {
      const int hi = i + 2 < rest.size() ? hexDigit(rest[i + 1]) : -1;
      const int lo = i + 2 < rest.size() ? hexDigit(rest[i + 2]) : -1;
      if (hi < 0 || lo < 0) {
        why = std::string("resource location \"") + uri + "\" has a malformed percent escape";
        return std::nullopt;
      }
      path += static_cast<char>(hi * 16 + lo);
      i += 2;
    } else {
      path += rest[i];
    }
  }
  // file:////abs and file:///abs both mean /abs on this platform.
  while (startsWith(path, "//")) path.erase(0, 1);
  if (kDriveLetters && startsWith(path, "/") && isDrive(path, 1)) path.erase(0, 1);
  while (path.size() > 1 && path.back() == '/') path.pop_back();
  if (!startsWith(path, "/") && !(kDriveLetters && isDrive(path, 0))) {
    why = std::string("resource location \"") + uri + "\" is not an absolute file URI";
    return std::nullopt;
  }
  return path;
}

}  // namespace rigidfmu
