// The number of members of an aggregate, found by brace-initializing it from ever more values of a
// type that converts to anything. It lets a hand-written field list be checked at compile time
// against the struct it describes. Counts right for members that are scalars or classes such as
// std::string; a C array or nested aggregate member would be miscounted (brace elision).
#pragma once

#include <cstddef>

namespace fnet {
namespace detail {

struct AnyMember {
  template <class T>
  operator T() const;  // never defined: only named in unevaluated requires-expressions
};

}  // namespace detail

template <class T, class... Members>
consteval std::size_t member_count() {
  if constexpr (requires { T{Members{}..., detail::AnyMember{}}; })
    return member_count<T, Members..., detail::AnyMember>();
  else
    return sizeof...(Members);
}

}  // namespace fnet
