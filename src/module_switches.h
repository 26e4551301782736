// Which optional modules this translation unit compiles in (see modules.h): the build
// sets RIGID_WITH_* per binary (by default all of them), and the code asks the
// constants below with `if constexpr`, so that both sides of a switch are compiled in
// every binary and only the chosen one is emitted: an absent module costs nothing in
// the step, and its library (FCL) is not linked.
#pragma once

#ifndef RIGID_WITH_SURFACES
#define RIGID_WITH_SURFACES 1
#endif
#ifndef RIGID_WITH_MEDIA
#define RIGID_WITH_MEDIA 1
#endif
#ifndef RIGID_WITH_COLLISIONS
#define RIGID_WITH_COLLISIONS 1
#endif
#ifndef RIGID_WITH_JOINTS
#define RIGID_WITH_JOINTS 1
#endif
#ifndef RIGID_WITH_MESHES
#define RIGID_WITH_MESHES 1
#endif
#if RIGID_WITH_COLLISIONS != RIGID_WITH_SURFACES
#error "surfaces and collisions come together (modules.h)"
#endif
#if RIGID_WITH_JOINTS && !RIGID_WITH_COLLISIONS
#error "joints come with collisions (modules.h)"
#endif

namespace rigid::modules {
constexpr bool kSurfaces = RIGID_WITH_SURFACES;
constexpr bool kMedia = RIGID_WITH_MEDIA;
constexpr bool kCollisions = RIGID_WITH_COLLISIONS;
constexpr bool kJoints = RIGID_WITH_JOINTS;
constexpr bool kMeshes = RIGID_WITH_MESHES;
}  // namespace rigid::modules
