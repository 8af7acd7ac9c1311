#include <nanobind/nanobind.h>
namespace nb = nanobind;
NB_MODULE(_cpp, m) { m.def("version", []() { return 1; }); }
