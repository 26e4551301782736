/* A C importer of one FMU binary, compiled for Linux (gcc, dlopen) and for Windows
 * (MinGW-w64, LoadLibrary; run under wine): the same calls on the linux64 .so and the
 * win64 .dll of one FMU, their results printed for tests/win64/test_win64.py to compare.
 * Compiled as it is, it drives an FMI 2.0 binary; with -DFMI3, an FMI 3.0 one (the
 * same calls by their FMI 3 names: the version's differences are the layer below,
 * the run and the abuse sample are one text for both).
 *
 *   fmu_driver LIBRARY GUID RESOURCES run STEPS H OUT [VR=VALUE | VR~AMPLITUDE]...
 *     instantiate; set each VR=VALUE (parameters, start values); initialise; STEPS steps
 *     of H s, each VR~AMPLITUDE input set to a triangle wave of that amplitude before
 *     step n (no libm call: the two C runtimes' sin may differ in the last bit); the
 *     Reals of OUT (comma-separated value references) printed at step 10 and every 100
 *     steps. Halfway, the FMU state is taken and serialised; at the end it is
 *     deserialised and set, and the second half is run again ("again" lines). Then
 *     Reset, initialise and 10 steps again ("reset" line), FreeInstance.
 *   fmu_driver LIBRARY GUID RESOURCES abuse VR
 *     a sample of bad calls: DoStep before initialisation, NaN into input VR, an
 *     unknown value reference; each call's status and the message it logged.
 * RESOURCES: FMI 2's resource URI, FMI 3's resource path. GUID: FMI 3's
 * instantiation token. LIBRARY and FMI 3's RESOURCES are UTF-8 with %XX escapes, which
 * the driver decodes: a non-ASCII path then reaches it intact whatever code page wine
 * gives argv (the library is opened by its wide-character name on Windows). Exit
 * status 0 when every call that should succeed did. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef FMI3
#include "fmi3Functions.h"
#define PREFIX "fmi3"
#else
#include "fmi2Functions.h"
#define PREFIX "fmi2"
#endif

#ifdef _WIN32
#include <windows.h>
typedef HMODULE Library;
static Library open_library(const char* path) {
  wchar_t wide[4096];
  if (!MultiByteToWideChar(CP_UTF8, 0, path, -1, wide, 4096)) return NULL;
  return LoadLibraryW(wide);
}
static void* find_symbol(Library lib, const char* name) { return (void*)GetProcAddress(lib, name); }
#else
#include <dlfcn.h>
typedef void* Library;
static Library open_library(const char* path) { return dlopen(path, RTLD_NOW | RTLD_LOCAL); }
static void* find_symbol(Library lib, const char* name) { return dlsym(lib, name); }
#endif

/* %XX escapes decoded in place. */
static void unescape(char* s) {
  char* out = s;
  for (; *s; ++s) {
    unsigned value;
    if (s[0] == '%' && s[1] && s[2] && sscanf(s + 1, "%2x", &value) == 1) {
      *out++ = (char)value;
      s += 2;
    } else {
      *out++ = *s;
    }
  }
  *out = '\0';
}

#define MAX_VRS 4096
#define MAX_SETTINGS 64

static char last_message[2048];

/* ---- the FMI version's layer: one function per call the driver makes ---------- */

#ifdef FMI3
typedef fmi3Instance Instance;
typedef fmi3FMUState State;
typedef fmi3ValueReference ValueReference;
typedef fmi3Status Status;
typedef fmi3Byte Byte;
#define OK fmi3OK

static void log_message(fmi3InstanceEnvironment env, fmi3Status status, fmi3String category, fmi3String message) {
  (void)env, (void)status, (void)category;
  snprintf(last_message, sizeof last_message, "%s", message);
}

static struct {
  fmi3InstantiateCoSimulationTYPE* InstantiateCoSimulation;
  fmi3FreeInstanceTYPE* FreeInstance;
  fmi3EnterInitializationModeTYPE* EnterInitializationMode;
  fmi3ExitInitializationModeTYPE* ExitInitializationMode;
  fmi3DoStepTYPE* DoStep;
  fmi3SetFloat64TYPE* SetFloat64;
  fmi3GetFloat64TYPE* GetFloat64;
  fmi3GetFMUStateTYPE* GetFMUState;
  fmi3SetFMUStateTYPE* SetFMUState;
  fmi3FreeFMUStateTYPE* FreeFMUState;
  fmi3SerializedFMUStateSizeTYPE* SerializedFMUStateSize;
  fmi3SerializeFMUStateTYPE* SerializeFMUState;
  fmi3DeserializeFMUStateTYPE* DeserializeFMUState;
  fmi3ResetTYPE* Reset;
} fmi;
// a list of names, laid out by hand
// clang-format off
#define FUNCTIONS(F)                                                                                        \
  F(InstantiateCoSimulation) F(FreeInstance) F(EnterInitializationMode) F(ExitInitializationMode) F(DoStep) \
  F(SetFloat64) F(GetFloat64) F(GetFMUState) F(SetFMUState) F(FreeFMUState) F(SerializedFMUStateSize)       \
  F(SerializeFMUState) F(DeserializeFMUState) F(Reset)
// clang-format on

static Instance instantiate(const char* token, const char* resources) {
  return fmi.InstantiateCoSimulation("driver", token, resources, fmi3False, fmi3False, fmi3False, fmi3False, NULL, 0,
                                     NULL, log_message, NULL);
}
/* FMI 3: part of EnterInitializationMode */
static Status setup(Instance c) {
  (void)c;
  return fmi3OK;
}
static Status enter_initialization(Instance c) {
  return fmi.EnterInitializationMode(c, fmi3False, 0.0, 0.0, fmi3False, 0.0);
}
static Status exit_initialization(Instance c) { return fmi.ExitInitializationMode(c); }
static Status set_reals(Instance c, const ValueReference vr[], size_t n, const double v[]) {
  return fmi.SetFloat64(c, vr, n, v, n);
}
static Status get_reals(Instance c, const ValueReference vr[], size_t n, double v[]) {
  return fmi.GetFloat64(c, vr, n, v, n);
}
static Status do_step(Instance c, double t, double h) {
  fmi3Boolean event = fmi3False, terminate = fmi3False, early = fmi3False;
  fmi3Float64 last = 0.0;
  return fmi.DoStep(c, t, h, fmi3True, &event, &terminate, &early, &last);
}
static Status get_state(Instance c, State* s) { return fmi.GetFMUState(c, s); }
static Status set_state(Instance c, State s) { return fmi.SetFMUState(c, s); }
static Status free_state(Instance c, State* s) { return fmi.FreeFMUState(c, s); }
static Status state_size(Instance c, State s, size_t* n) { return fmi.SerializedFMUStateSize(c, s, n); }
static Status serialize(Instance c, State s, Byte b[], size_t n) { return fmi.SerializeFMUState(c, s, b, n); }
static Status deserialize(Instance c, const Byte b[], size_t n, State* s) {
  return fmi.DeserializeFMUState(c, b, n, s);
}
static Status reset(Instance c) { return fmi.Reset(c); }
static void free_instance(Instance c) { fmi.FreeInstance(c); }
#else
typedef fmi2Component Instance;
typedef fmi2FMUstate State;
typedef fmi2ValueReference ValueReference;
typedef fmi2Status Status;
typedef fmi2Byte Byte;
#define OK fmi2OK

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
// a list of names, laid out by hand
// clang-format off
#define FUNCTIONS(F)                                                                                              \
  F(Instantiate) F(FreeInstance) F(SetupExperiment) F(EnterInitializationMode) F(ExitInitializationMode) F(DoStep) \
  F(SetReal) F(GetReal) F(GetFMUstate) F(SetFMUstate) F(FreeFMUstate) F(SerializedFMUstateSize)                  \
  F(SerializeFMUstate) F(DeSerializeFMUstate) F(Reset)
// clang-format on

static fmi2CallbackFunctions callbacks = {log_message, allocate, free, NULL, NULL};
static Instance instantiate(const char* guid, const char* resources) {
  return fmi.Instantiate("driver", fmi2CoSimulation, guid, resources, &callbacks, fmi2False, fmi2False);
}
static Status setup(Instance c) { return fmi.SetupExperiment(c, fmi2False, 0.0, 0.0, fmi2False, 0.0); }
static Status enter_initialization(Instance c) { return fmi.EnterInitializationMode(c); }
static Status exit_initialization(Instance c) { return fmi.ExitInitializationMode(c); }
static Status set_reals(Instance c, const ValueReference vr[], size_t n, const double v[]) {
  return fmi.SetReal(c, vr, n, v);
}
static Status get_reals(Instance c, const ValueReference vr[], size_t n, double v[]) {
  return fmi.GetReal(c, vr, n, v);
}
static Status do_step(Instance c, double t, double h) { return fmi.DoStep(c, t, h, fmi2True); }
static Status get_state(Instance c, State* s) { return fmi.GetFMUstate(c, s); }
static Status set_state(Instance c, State s) { return fmi.SetFMUstate(c, s); }
static Status free_state(Instance c, State* s) { return fmi.FreeFMUstate(c, s); }
static Status state_size(Instance c, State s, size_t* n) { return fmi.SerializedFMUstateSize(c, s, n); }
static Status serialize(Instance c, State s, Byte b[], size_t n) { return fmi.SerializeFMUstate(c, s, b, n); }
static Status deserialize(Instance c, const Byte b[], size_t n, State* s) {
  return fmi.DeSerializeFMUstate(c, b, n, s);
}
static Status reset(Instance c) { return fmi.Reset(c); }
static void free_instance(Instance c) { fmi.FreeInstance(c); }
#endif

static int load(Library lib) {
#define LOAD(f)                                                        \
  if (!(*(void**)(&fmi.f) = find_symbol(lib, PREFIX #f))) {            \
    fprintf(stderr, "the library does not export %s%s\n", PREFIX, #f); \
    return 0;                                                          \
  }
  FUNCTIONS(LOAD)
#undef LOAD
  return 1;
}

/* ---- the calls, the same for both versions ------------------------------------ */

#define CHECK(call)                                                          \
  do {                                                                       \
    Status s_ = (call);                                                      \
    if (s_ != OK) {                                                          \
      fprintf(stderr, "%s returned %d: %s\n", #call, (int)s_, last_message); \
      return 3;                                                              \
    }                                                                        \
  } while (0)

typedef struct {
  ValueReference vr;
  double value;
  int input; /* 1: value is the amplitude of an input signal */
} Setting;

static ValueReference outputs[MAX_VRS];
static size_t n_outputs;
static Setting settings[MAX_SETTINGS];
static size_t n_settings;

static void print_outputs(Instance c, const char* tag, int step) {
  static double values[MAX_VRS];
  if (get_reals(c, outputs, n_outputs, values) != OK) {
    printf("%s %d getReal failed\n", tag, step);
    return;
  }
  printf("%s %d", tag, step);
  for (size_t i = 0; i < n_outputs; ++i) printf(" %.17g", values[i]);
  printf("\n");
}

static int initialise(Instance c) {
  CHECK(setup(c));
  for (size_t i = 0; i < n_settings; ++i)
    if (!settings[i].input) CHECK(set_reals(c, &settings[i].vr, 1, &settings[i].value));
  CHECK(enter_initialization(c));
  CHECK(exit_initialization(c));
  return 0;
}

static int step(Instance c, int n, double h) {
  for (size_t i = 0; i < n_settings; ++i)
    if (settings[i].input) {
      const double phase = (n % 200) / 50.0; /* 0..4: up, down, down, up */
      const double u = settings[i].value * (phase < 1 ? phase : phase < 3 ? 2 - phase : phase - 4);
      CHECK(set_reals(c, &settings[i].vr, 1, &u));
    }
  CHECK(do_step(c, n * h, h));
  return 0;
}

static int run(Instance c, int steps, double h) {
  State half = NULL, loaded = NULL;
  Byte* bytes = NULL;
  size_t size = 0;
  int r;
  if ((r = initialise(c))) return r;
  for (int n = 0; n < steps; ++n) {
    if (n == steps / 2) {
      CHECK(get_state(c, &half));
      CHECK(state_size(c, half, &size));
      bytes = (Byte*)malloc(size);
      CHECK(serialize(c, half, bytes, size));
      CHECK(free_state(c, &half));
    }
    if ((r = step(c, n, h))) return r;
    if ((n + 1) == 10 || (n + 1) % 100 == 0) print_outputs(c, "step", n + 1);
  }
  CHECK(deserialize(c, bytes, size, &loaded));
  CHECK(set_state(c, loaded));
  CHECK(free_state(c, &loaded));
  free(bytes);
  for (int n = steps / 2; n < steps; ++n) {
    if ((r = step(c, n, h))) return r;
    if ((n + 1) % 100 == 0) print_outputs(c, "again", n + 1);
  }
  CHECK(reset(c));
  if ((r = initialise(c))) return r;
  for (int n = 0; n < 10; ++n)
    if ((r = step(c, n, h))) return r;
  print_outputs(c, "reset", 10);
  return 0;
}

static void report(const char* what, Status status) {
  printf("%s status %d: %s\n", what, (int)status, last_message);
  last_message[0] = '\0';
}

static int abuse(Instance c, ValueReference input) {
  const double nan = NAN, one = 1.0;
  const ValueReference unknown = 4000000000u;
  double value = 0.0;
  int r;
  report("doStep before initialisation", do_step(c, 0.0, 0.01));
  if ((r = initialise(c))) return r;
  report("NaN input", set_reals(c, &input, 1, &nan));
  report("unknown value reference", get_reals(c, &unknown, 1, &value));
  report("unknown value reference set", set_reals(c, &unknown, 1, &one));
  CHECK(do_step(c, 0.0, 0.01)); /* the instance is still usable */
  return 0;
}

int main(int argc, char** argv) {
  if (argc < 6) {
    fprintf(stderr, "usage: %s LIBRARY GUID RESOURCES run STEPS H OUT [VR=V|VR~A]... | abuse VR\n", argv[0]);
    return 2;
  }
  unescape(argv[1]);
#ifdef FMI3
  unescape(argv[3]);
#endif
  Library lib = open_library(argv[1]);
  if (!lib) {
    fprintf(stderr, "cannot load %s\n", argv[1]);
    return 2;
  }
  if (!load(lib)) return 2;
  Instance c = instantiate(argv[2], argv[3]);
  if (!c) {
    fprintf(stderr, "instantiation failed: %s\n", last_message);
    return 3;
  }
  int result;
  if (strcmp(argv[4], "abuse") == 0) {
    result = abuse(c, (ValueReference)strtoul(argv[5], NULL, 10));
  } else if (strcmp(argv[4], "run") == 0 && argc >= 8) {
    for (char* p = argv[7]; *p && n_outputs < MAX_VRS;) {
      outputs[n_outputs++] = (ValueReference)strtoul(p, &p, 10);
      if (*p == ',') ++p;
    }
    for (int i = 8; i < argc && n_settings < MAX_SETTINGS; ++i) {
      char* rest;
      settings[n_settings].vr = (ValueReference)strtoul(argv[i], &rest, 10);
      settings[n_settings].input = *rest == '~';
      settings[n_settings].value = strtod(rest + 1, NULL);
      ++n_settings;
    }
    result = run(c, atoi(argv[5]), strtod(argv[6], NULL));
  } else {
    fprintf(stderr, "unknown mode %s\n", argv[4]);
    result = 2;
  }
  free_instance(c);
  printf("done %d\n", result);
  return result;
}
