/* A C importer of one FMU binary, compiled for Linux (gcc, dlopen) and for Windows
 * (MinGW-w64, LoadLibrary; run under wine): the same calls on the linux64 .so and the
 * win64 .dll of one FMU, their results printed for tests/win64/test_win64.py to compare.
 *
 *   fmu_driver LIBRARY GUID RESOURCE_URI run STEPS H OUT [VR=VALUE | VR~AMPLITUDE]...
 *     instantiate; set each VR=VALUE (parameters, start values); initialise; STEPS steps
 *     of H s, each VR~AMPLITUDE input set to a triangle wave of that amplitude before
 *     step n (no libm call: the two C runtimes' sin may differ in the last bit); the
 *     Reals of OUT (comma-separated value references) printed at step 10 and every 100
 *     steps. Halfway, the FMU state is taken and serialised; at the end it is
 *     deserialised and set, and the second half is run again ("again" lines). Then
 *     fmi2Reset, initialise and 10 steps again ("reset" line), fmi2FreeInstance.
 *   fmu_driver LIBRARY GUID RESOURCE_URI abuse VR
 *     a sample of bad calls: fmi2DoStep before initialisation, NaN into input VR, an
 *     unknown value reference; each call's status and the message it logged.
 * Exit status 0 when every call that should succeed did. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi2Functions.h"

#ifdef _WIN32
#include <windows.h>
typedef HMODULE Library;
static Library open_library(const char* path) { return LoadLibraryA(path); }
static void* find_symbol(Library lib, const char* name) { return (void*)GetProcAddress(lib, name); }
#else
#include <dlfcn.h>
typedef void* Library;
static Library open_library(const char* path) { return dlopen(path, RTLD_NOW | RTLD_LOCAL); }
static void* find_symbol(Library lib, const char* name) { return dlsym(lib, name); }
#endif

#define MAX_VRS 4096
#define MAX_SETTINGS 64

static char last_message[2048];

static void log_message(fmi2ComponentEnvironment env, fmi2String name, fmi2Status status, fmi2String category,
                        fmi2String message, ...) {
  va_list ap;
  (void)env, (void)name, (void)status, (void)category;
  va_start(ap, message);
  vsnprintf(last_message, sizeof last_message, message, ap);
  va_end(ap);
}

static void* allocate(size_t n, size_t size) { return calloc(n, size); }

static struct {
  fmi2InstantiateTYPE* Instantiate;
  fmi2FreeInstanceTYPE* FreeInstance;
  fmi2SetupExperimentTYPE* SetupExperiment;
  fmi2EnterInitializationModeTYPE* EnterInitializationMode;
  fmi2ExitInitializationModeTYPE* ExitInitializationMode;
  fmi2DoStepTYPE* DoStep;
  fmi2SetRealTYPE* SetReal;
  fmi2GetRealTYPE* GetReal;
  fmi2GetFMUstateTYPE* GetFMUstate;
  fmi2SetFMUstateTYPE* SetFMUstate;
  fmi2FreeFMUstateTYPE* FreeFMUstate;
  fmi2SerializedFMUstateSizeTYPE* SerializedFMUstateSize;
  fmi2SerializeFMUstateTYPE* SerializeFMUstate;
  fmi2DeSerializeFMUstateTYPE* DeSerializeFMUstate;
  fmi2ResetTYPE* Reset;
} fmi;

static int load(Library lib) {
#define LOAD(f)                                                   \
  if (!(*(void**)&fmi.f = find_symbol(lib, "fmi2" #f))) {          \
    fprintf(stderr, "the library does not export fmi2%s\n", #f);  \
    return 0;                                                     \
  }
  LOAD(Instantiate) LOAD(FreeInstance) LOAD(SetupExperiment) LOAD(EnterInitializationMode)
  LOAD(ExitInitializationMode) LOAD(DoStep) LOAD(SetReal) LOAD(GetReal) LOAD(GetFMUstate)
  LOAD(SetFMUstate) LOAD(FreeFMUstate) LOAD(SerializedFMUstateSize) LOAD(SerializeFMUstate)
  LOAD(DeSerializeFMUstate) LOAD(Reset)
#undef LOAD
  return 1;
}

#define CHECK(call)                                                                  \
  do {                                                                               \
    fmi2Status s_ = (call);                                                          \
    if (s_ != fmi2OK) {                                                              \
      fprintf(stderr, "%s returned %d: %s\n", #call, (int)s_, last_message);         \
      return 3;                                                                      \
    }                                                                                \
  } while (0)

typedef struct {
  fmi2ValueReference vr;
  double value;
  int input; /* 1: value is the amplitude of an input signal */
} Setting;

static fmi2ValueReference outputs[MAX_VRS];
static size_t n_outputs;
static Setting settings[MAX_SETTINGS];
static size_t n_settings;

static void print_outputs(fmi2Component c, const char* tag, int step) {
  static double values[MAX_VRS];
  if (fmi.GetReal(c, outputs, n_outputs, values) != fmi2OK) {
    printf("%s %d getReal failed\n", tag, step);
    return;
  }
  printf("%s %d", tag, step);
  for (size_t i = 0; i < n_outputs; ++i) printf(" %.17g", values[i]);
  printf("\n");
}

static int initialise(fmi2Component c) {
  CHECK(fmi.SetupExperiment(c, fmi2False, 0.0, 0.0, fmi2False, 0.0));
  for (size_t i = 0; i < n_settings; ++i)
    if (!settings[i].input) CHECK(fmi.SetReal(c, &settings[i].vr, 1, &settings[i].value));
  CHECK(fmi.EnterInitializationMode(c));
  CHECK(fmi.ExitInitializationMode(c));
  return 0;
}

static int step(fmi2Component c, int n, double h) {
  for (size_t i = 0; i < n_settings; ++i)
    if (settings[i].input) {
      const double phase = (n % 200) / 50.0; /* 0..4: up, down, down, up */
      const double u = settings[i].value * (phase < 1 ? phase : phase < 3 ? 2 - phase : phase - 4);
      CHECK(fmi.SetReal(c, &settings[i].vr, 1, &u));
    }
  CHECK(fmi.DoStep(c, n * h, h, fmi2True));
  return 0;
}

static int run(fmi2Component c, int steps, double h) {
  fmi2FMUstate half = NULL, loaded = NULL;
  fmi2Byte* bytes = NULL;
  size_t size = 0;
  int r;
  if ((r = initialise(c))) return r;
  for (int n = 0; n < steps; ++n) {
    if (n == steps / 2) {
      CHECK(fmi.GetFMUstate(c, &half));
      CHECK(fmi.SerializedFMUstateSize(c, half, &size));
      bytes = (fmi2Byte*)malloc(size);
      CHECK(fmi.SerializeFMUstate(c, half, bytes, size));
      CHECK(fmi.FreeFMUstate(c, &half));
    }
    if ((r = step(c, n, h))) return r;
    if ((n + 1) == 10 || (n + 1) % 100 == 0) print_outputs(c, "step", n + 1);
  }
  CHECK(fmi.DeSerializeFMUstate(c, bytes, size, &loaded));
  CHECK(fmi.SetFMUstate(c, loaded));
  CHECK(fmi.FreeFMUstate(c, &loaded));
  free(bytes);
  for (int n = steps / 2; n < steps; ++n) {
    if ((r = step(c, n, h))) return r;
    if ((n + 1) % 100 == 0) print_outputs(c, "again", n + 1);
  }
  CHECK(fmi.Reset(c));
  if ((r = initialise(c))) return r;
  for (int n = 0; n < 10; ++n)
    if ((r = step(c, n, h))) return r;
  print_outputs(c, "reset", 10);
  return 0;
}

static void report(const char* what, fmi2Status status) {
  printf("%s status %d: %s\n", what, (int)status, last_message);
  last_message[0] = '\0';
}

static int abuse(fmi2Component c, fmi2ValueReference input) {
  const double nan = NAN, one = 1.0;
  const fmi2ValueReference unknown = 4000000000u;
  double value = 0.0;
  int r;
  report("doStep before initialisation", fmi.DoStep(c, 0.0, 0.01, fmi2True));
  if ((r = initialise(c))) return r;
  report("NaN input", fmi.SetReal(c, &input, 1, &nan));
  report("unknown value reference", fmi.GetReal(c, &unknown, 1, &value));
  report("unknown value reference set", fmi.SetReal(c, &unknown, 1, &one));
  CHECK(fmi.DoStep(c, 0.0, 0.01, fmi2True)); /* the instance is still usable */
  return 0;
}

int main(int argc, char** argv) {
  if (argc < 6) {
    fprintf(stderr, "usage: %s LIBRARY GUID RESOURCE_URI run STEPS H OUT [VR=V|VR~A]... | abuse VR\n", argv[0]);
    return 2;
  }
  Library lib = open_library(argv[1]);
  if (!lib) {
    fprintf(stderr, "cannot load %s\n", argv[1]);
    return 2;
  }
  if (!load(lib)) return 2;
  fmi2CallbackFunctions callbacks = {log_message, allocate, free, NULL, NULL};
  fmi2Component c = fmi.Instantiate("driver", fmi2CoSimulation, argv[2], argv[3], &callbacks, fmi2False, fmi2False);
  if (!c) {
    fprintf(stderr, "fmi2Instantiate failed: %s\n", last_message);
    return 3;
  }
  int result;
  if (strcmp(argv[4], "abuse") == 0) {
    result = abuse(c, (fmi2ValueReference)strtoul(argv[5], NULL, 10));
  } else if (strcmp(argv[4], "run") == 0 && argc >= 8) {
    for (char* p = argv[7]; *p && n_outputs < MAX_VRS;) {
      outputs[n_outputs++] = (fmi2ValueReference)strtoul(p, &p, 10);
      if (*p == ',') ++p;
    }
    for (int i = 8; i < argc && n_settings < MAX_SETTINGS; ++i) {
      char* rest;
      settings[n_settings].vr = (fmi2ValueReference)strtoul(argv[i], &rest, 10);
      settings[n_settings].input = *rest == '~';
      settings[n_settings].value = strtod(rest + 1, NULL);
      ++n_settings;
    }
    result = run(c, atoi(argv[5]), strtod(argv[6], NULL));
  } else {
    fprintf(stderr, "unknown mode %s\n", argv[4]);
    result = 2;
  }
  fmi.FreeInstance(c);
  printf("done %d\n", result);
  return result;
}
