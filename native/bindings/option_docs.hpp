// Option structs bound from the field tables their headers declare (`S::fields(f)` calls
// f(name, member pointer, doc) once per field), so no binding writes a field's name or doc
// again. Docstrings end with the field's default, read from a default-constructed struct: the
// generated stubs then show the defaults the C++ header declares, and no binding repeats them.
#pragma once

#include <string>
#include <type_traits>
#include <utility>

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

namespace fairlines::option_docs {

namespace py = pybind11;

/// True for a struct with a field table (a nested options struct: its default has no useful repr).
template <typename T, typename = void>
struct has_fields : std::false_type {};
template <typename T>
struct has_fields<T, std::void_t<decltype(T::fields(std::declval<void (*)(const char*, int T::*, const char*)>()))>>
    : std::true_type {};

/// `doc` followed by " (default <Python repr of value>)".
template <typename T>
std::string with_default(const char* doc, const T& value) {
  return std::string(doc) + " (default " + py::repr(py::cast(value)).template cast<std::string>() + ")";
}

/// def_readwrite of an options field, its docstring ending with the field's default (a nested
/// options struct keeps the plain doc: its own fields carry the defaults).
template <typename Options, typename T>
py::class_<Options>& field(py::class_<Options>& cls, const char* name, T Options::*member, const char* doc) {
  if constexpr (has_fields<T>::value) {
    return cls.def_readwrite(name, member, doc);
  } else {
    const std::string text = with_default(doc, Options{}.*member);
    return cls.def_readwrite(name, member, text.c_str());
  }
}

/// An enum field read and set by its name (to_name(value) -> name, parse(name) -> value).
template <typename Options, typename E, typename Name, typename Parse>
void def_named(py::class_<Options>& c, const char* name, E Options::*member, const char* doc, Name to_name,
               Parse parse) {
  c.def_property(
      name, [member, to_name](const Options& o) { return to_name(o.*member); },
      [member, parse](Options& o, const std::string& v) { o.*member = parse(v); },
      with_default(doc, to_name(Options{}.*member)).c_str());
}

/// A special binder for the fields of member type T: bind(cls, name, member, doc) binds each
/// (returns true for a field it bound, false for any other).
template <typename T, typename Bind>
auto for_type(Bind bind) {
  return [bind](auto& cls, const char* name, auto member, const char* doc) {
    using Options = typename std::remove_reference_t<decltype(cls)>::type;
    if constexpr (std::is_same_v<decltype(member), T Options::*>) {
      bind(cls, name, member, doc);
      return true;
    } else {
      return false;
    }
  };
}

/// A special binder for one field: bind(cls, name, doc) binds `which`.
template <typename Options, typename T, typename Bind>
auto for_member(T Options::*which, Bind bind) {
  return [which, bind](py::class_<Options>& cls, const char* name, auto member, const char* doc) {
    if constexpr (std::is_same_v<decltype(member), T Options::*>) {
      if (member == which) {
        bind(cls, name, doc);
        return true;
      }
    }
    return false;
  };
}

/// A special binder for the fields of enum type E (parse's result): read and set by name.
template <typename Name, typename Parse>
auto by_name(Name to_name, Parse parse) {
  using E = std::invoke_result_t<Parse, const std::string&>;
  return for_type<E>([to_name, parse](auto& cls, const char* name, auto member, const char* doc) {
    def_named(cls, name, member, doc, to_name, parse);
  });
}

/// Every field of Options' table bound with `field`, except those one of `specials` binds (a
/// field whose Python value is converted).
template <typename Options, typename... Special>
py::class_<Options>& bind_fields(py::class_<Options>& cls, Special... specials) {
  Options::fields([&](const char* name, auto member, const char* doc) {
    if (!(specials(cls, name, member, doc) || ...)) field(cls, name, member, doc);
  });
  return cls;
}

/// An options class with a default constructor and every field of its table.
template <typename Options>
py::class_<Options> bind_options(py::module_& m, const char* name, const char* doc) {
  py::class_<Options> cls(m, name, doc);
  cls.def(py::init<>());
  return bind_fields(cls);
}

}  // namespace fairlines::option_docs
