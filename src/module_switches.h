// Which optional modules this translation unit compiles in (see modules.h): the build
// sets RIGID_WITH_* per binary; by default all of them.
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
#if RIGID_WITH_COLLISIONS != RIGID_WITH_SURFACES
#error "surfaces and collisions come together (modules.h)"
#endif
