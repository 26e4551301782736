#include "guid.h"

#include <cstdint>
#include <cstdio>

namespace rigidfmu {

namespace {

// 64-bit FNV-1a; two passes with different offset bases give 128 bits. Not a
// cryptographic hash: it only has to tell scenes apart.
uint64_t fnv1a(const std::string& text, uint64_t basis) {
  uint64_t h = basis;
  for (unsigned char c : text) {
    h ^= c;
    h *= 0x100000001b3ULL;
  }
  return h;
}

}  // namespace

std::string sceneGuid(const rigid::Scene& scene) {
  const std::string content = std::string(kLayoutVersion) + "\n" + scene.canonicalJson;
  const uint64_t a = fnv1a(content, 0xcbf29ce484222325ULL);
  const uint64_t b = fnv1a(content, 0x84222325cbf29ce4ULL);
  char buf[40];
  std::snprintf(buf, sizeof buf, "{%08x-%04x-%04x-%04x-%012llx}", static_cast<unsigned>(a >> 32),
                static_cast<unsigned>((a >> 16) & 0xffff), static_cast<unsigned>(a & 0xffff),
                static_cast<unsigned>(b >> 48), static_cast<unsigned long long>(b & 0xffffffffffffULL));
  return buf;
}

}  // namespace rigidfmu
