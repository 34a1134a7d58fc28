// GDCONTACT_API marks the public C++ API: the only symbols a shared libgdcontact exports (it is
// built with -fvisibility=hidden, so everything else — gdc::detail::, gdc::ode::detail:: and every
// helper — stays internal). It is harmless for the static library. Every public function or class
// declared in include/gdcontact/*.hpp carries it; a new one must too, or a program linked against
// the shared library gets an undefined reference.
#pragma once

#if defined(__GNUC__) || defined(__clang__)
#define GDCONTACT_API __attribute__((visibility("default")))
#else
#define GDCONTACT_API
#endif
