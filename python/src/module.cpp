// The extension module pierce._core; the package `pierce` (pierce/__init__.py) re-exports it.
#include <pybind11/pybind11.h>

#include "common.h"
#include "pierce/error.h"
#include "progress.h"

namespace pyb = pybind11;

PYBIND11_MODULE(_core, m) {
  using namespace pierce::py;
  m.doc() = "Pierce: exact multi-hit ray traversal (C++ core bindings).";

  // Bad input keeps the core's message; it is a ValueError so generic handlers catch it too.
  pyb::register_exception<pierce::InputError>(m, "InputError", PyExc_ValueError);
  pyb::register_exception<Cancelled>(m, "Cancelled", PyExc_Exception);

  pyb::class_<CancelToken>(m, "CancelToken",
                           "Pass as cancel=... to a long call; cancel() (from any thread) stops it with "
                           "pierce.Cancelled.")
      .def(pyb::init<>())
      .def("cancel", &CancelToken::cancel)
      .def("reset", &CancelToken::reset)
      .def_property_readonly("cancelled", &CancelToken::cancelled);

  bind_scene(m);
  bind_hits(m);
  bind_io(m);
  bind_thickness(m);
  bind_overlaps(m);
  bind_partitions(m);
  bind_shotline(m);
}
