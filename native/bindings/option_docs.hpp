// Docstrings of bound option fields that end with the field's default, read from a
// default-constructed options struct: the generated stubs then show the defaults the C++
// header declares, and no binding repeats them.
#pragma once

#include <string>

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

namespace fairlines::option_docs {

namespace py = pybind11;

/// `doc` followed by " (default <Python repr of value>)".
template <typename T>
std::string with_default(const char* doc, const T& value) {
  return std::string(doc) + " (default " + py::repr(py::cast(value)).template cast<std::string>() + ")";
}

/// def_readwrite of an options field, its docstring ending with the field's default.
template <typename Options, typename T>
py::class_<Options>& field(py::class_<Options>& cls, const char* name, T Options::*member, const char* doc) {
  const std::string text = with_default(doc, Options{}.*member);
  return cls.def_readwrite(name, member, text.c_str());
}

}  // namespace fairlines::option_docs
