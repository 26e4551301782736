// What every FMI entry point does around its work (fmi2_functions.cpp,
// fmi3_functions.cpp): check the instance and its state, and catch every exception at
// the C boundary.
#pragma once

#include <cstring>
#include <exception>
#include <new>
#include <string>

#include "instance.h"

namespace rigidfmu {

// The bits of an enumeration argument (fmi2Type, fmi2StatusKind) as an int. A master
// may pass any value, and reading one outside the enumeration's range as the enum type
// is undefined behaviour (UBSan reports it), so it is copied out and compared as an int.
template <class Enum>
int enumBits(const Enum& e) {
  static_assert(sizeof(Enum) == sizeof(int), "FMI enumerations are int-sized here");
  int bits;
  std::memcpy(&bits, &e, sizeof bits);
  return bits;
}

// Runs body for a valid instance in an allowed state; any exception becomes fmi2Error
// (and the Error state, since the instance may be half-updated). The FMI 3 entry points
// use it too: their statuses have the same values.
template <class Body>
inline fmi2Status guarded(fmi2Component c, const char* function, unsigned allowed, Body body) {
  if (!c) return fmi2Error;  // no instance, so no logger to tell
  Instance* instance = static_cast<Instance*>(c);
  try {
    if (!instance->allowedIn(allowed, function)) return fmi2Error;
    return body(*instance);
  } catch (const std::bad_alloc&) {
    instance->enterErrorState();
    return instance->error(std::string(function) + ": out of memory");
  } catch (const std::exception& e) {
    instance->enterErrorState();
    return instance->error(std::string(function) + ": " + e.what());
  } catch (...) {
    instance->enterErrorState();
    return instance->error(std::string(function) + ": unknown exception");
  }
}

inline fmi2Status unsupported(fmi2Component c, const char* function, unsigned states, const char* why) {
  return guarded(c, function, states,
                 [&](Instance& i) { return i.error(std::string(function) + ": not supported (" + why + ")"); });
}

}  // namespace rigidfmu
