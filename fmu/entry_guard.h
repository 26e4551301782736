// What every FMI entry point does around its work, in either version (fmi2_functions.cpp
// and fmi3_functions.cpp map the Status it returns onto their own): check the instance
// and its state, name the call for its messages, and catch every exception at the C
// boundary.
#pragma once

#include <exception>
#include <new>
#include <string>

#include "instance.h"
#include "status.h"

namespace rigidfmu {

// Runs body for a valid instance in an allowed state; `function`, the function the
// importer called, names every message of the call (Instance::enter). Any exception
// becomes Error (and the Error state, since the instance may be half-updated).
template <class Body>
inline Status guarded(Instance* instance, const char* function, unsigned allowed, Body body) {
  if (!instance) return Status::Error;  // no instance, so no logger to tell
  try {
    if (!instance->enter(function, allowed)) return Status::Error;
    return body(*instance);
  } catch (const std::bad_alloc&) {
    instance->enterErrorState();
    return instance->error("out of memory");
  } catch (const std::exception& e) {
    instance->enterErrorState();
    return instance->error(e.what());
  } catch (...) {
    instance->enterErrorState();
    return instance->error("unknown exception");
  }
}

// A function this FMU does not support: Error, "<function>: not supported (why)".
inline Status unsupported(Instance* instance, const char* function, unsigned allowed, const char* why) {
  return guarded(instance, function, allowed,
                 [&](Instance& i) { return i.error(std::string("not supported (") + why + ")"); });
}

}  // namespace rigidfmu
