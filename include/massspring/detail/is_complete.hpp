#pragma once
/// @file
/// @brief is_complete_v<T>: whether T is a complete type where it is asked, so that a function
/// whose code lives in a header the caller has not included can say which header in a
/// static_assert instead of an incomplete-type error.

#include <type_traits>

namespace massspring::detail {

template <class T, class = void>
struct is_complete : std::false_type {};
template <class T>
struct is_complete<T, std::void_t<decltype(sizeof(T))>> : std::true_type {};
/// @brief True when T is complete (ask it only of a type a template depends on).
template <class T>
inline constexpr bool is_complete_v = is_complete<T>::value;

}  // namespace massspring::detail
