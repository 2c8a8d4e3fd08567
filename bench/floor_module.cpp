// The floor for call-overhead ratios: the cheapest pybind11 calls there are.

#include <pybind11/pybind11.h>

namespace py = pybind11;

namespace {
struct Empty {
    double value = 1.0;
};
} // namespace

PYBIND11_MODULE(_spear_bench_floor, m) {
    m.def("noop", [] {});
    py::class_<Empty>(m, "Empty")
        .def(py::init<>())
        .def("noop", [](const Empty&) {})
        .def("noop_kw", [](const Empty&, double) {}, py::kw_only(), py::arg("value"))
        .def_readwrite("value", &Empty::value);
}
