#pragma once
// Debian's Simbody 3.7 is built without NDEBUG and SimTK::CacheEntryInfo changes layout with it: code that
// includes Simbody with NDEBUG defined corrupts the heap ("Stage::getName(): illegal level").
#ifdef NDEBUG
#warning "sinew/simbody: NDEBUG is defined but Debian's Simbody 3.7 is built without it; State caches will be corrupted. Compile Simbody-facing code without -DNDEBUG (CMake build type None with your own -O flags)."
#endif
