#pragma once
// A fixture: deliberately not clang-formatted.
namespace fixture {
inline int   twice( int x ){return 2*x;}
}  // namespace fixture
