// The resource location an importer passes to fmi2Instantiate, as a local path.
#pragma once

#include <optional>
#include <string>

namespace rigidfmu {

// Accepts file:///abs, file:/abs, file:////abs, file://localhost/abs and a plain
// absolute path, percent-encoded or not. Returns the directory without a trailing
// slash, or nullopt (with the reason in `why`) for anything else.
std::optional<std::string> resourceDirectory(const char* uri, std::string& why);

}  // namespace rigidfmu
