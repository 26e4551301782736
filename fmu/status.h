// The instance's answers and messages in no FMI version's types: the five statuses
// both versions define, and the importer's logger as the adapter of its version wraps it
// (fmi2_functions.cpp, fmi3_functions.cpp map both onto their own types).
#pragma once

#include <functional>
#include <string>

namespace rigidfmu {

// The status of a call, in the order (and with the meaning) of fmi2Status and fmi3Status.
enum class Status { OK, Warning, Discard, Error, Fatal };

// The importer's logger: a status, one of the declared log categories and the message,
// as the importer is to read it (plain text, not a printf format; the FMI 2 adapter
// doubles its '%'). Empty when the importer gave none.
using Logger = std::function<void(Status status, const char* category, const std::string& message)>;

}  // namespace rigidfmu
