// Option structs as Python classes. The keyword-only constructor's defaults are read from a default-constructed
// C++ struct, so the two languages cannot drift; values are checked by the core when a call uses them, with
// the core's messages (ValueError). Values of the wrong type (a negative or float count) raise TypeError.
#pragma once

#include <string>

#include <pybind11/pybind11.h>

template <class T, class M>
struct OptionField {
  const char* name;
  M T::*member;
  const char* doc;
};

template <class T, class M>
OptionField<T, M> option(const char* name, M T::*member, const char* doc) {
  return {name, member, doc};
}

// class Name(*, field=default, ...) with read-write fields, copy.copy and a repr that lists them.
template <class T, class... M>
pybind11::class_<T> bind_options(pybind11::module_& m, const char* name, const char* doc,
                                 OptionField<T, M>... fields) {
  namespace py = pybind11;
  const T defaults{};
  py::class_<T> cls(m, name, doc);
  cls.def(py::init([fields...](const M&... values) {
            T t;
            ((t.*(fields.member) = values), ...);
            return t;
          }),
          py::kw_only(), (py::arg(fields.name) = defaults.*(fields.member))...);
  (cls.def_readwrite(fields.name, fields.member, fields.doc), ...);
  // A copy to change one field of (a plan's options for a part of its work), never the shared original.
  cls.def("__copy__", [](const T& t) { return t; });
  cls.def("__repr__", [type = std::string(name), fields...](const T& t) {
    std::string s = type + "(", separator;
    ((s += separator + fields.name + "=" +
           py::repr(py::cast(t.*(fields.member))).template cast<std::string>(),
      separator = ", "),
     ...);
    return s + ")";
  });
  return cls;
}
