// The in-process engine module, spear._spear_engine: the generated bindings of every engine class,
// the frame loop, and the dynamic API.

#include <pybind11/pybind11.h>

#include "core/pybind/dynamic_access.h"
#include "core/pybind/errors.h"
#include "core/pybind/object_ref.h"
#include "core/world/engine.h"
#include "core/world/object_access.h"

namespace py = pybind11;

void spear_bind_engine(py::module_& m);

namespace {
void checkFrame(sp::reflect::ObjectBase& object, std::string_view context) {
    sp::world::checkObjectAccess(object, context);
}
} // namespace

PYBIND11_MODULE(_spear_engine, m) {
    m.doc() = "spear's in-process engine (generated bindings; use the spear package, not this module)";
    sp::pybind::registerErrorTranslator();
    sp::pybind::setAccessCheck(&checkFrame);
    spear_bind_engine(m);
    sp::pybind::bindDynamicAccess(m, "spear._engine.api");

    using sp::world::Engine;
    py::class_<Engine>(m, "Engine", "The engine: its worlds and the frame loop.")
        .def(py::init([](double fixedDeltaSeconds, bool editor, std::string scene) {
                 return std::make_unique<Engine>(
                     Engine::Settings{fixedDeltaSeconds, editor, std::move(scene)});
             }),
             py::kw_only(), py::arg("fixed_delta_seconds") = 1.0 / 60.0, py::arg("editor") = false,
             py::arg("scene") = "")
        .def("get_game_world", [](Engine& e) { return sp::pybind::wrapObject(&e.GetGameWorld()); })
        .def("get_editor_world",
             [](Engine& e) -> py::object {
                 UWorld* world = e.GetEditorWorld();
                 return world ? py::object(sp::pybind::wrapObject(world)) : py::none();
             })
        .def("begin_frame", &Engine::beginFrame)
        .def("execute_frame", &Engine::executeFrame)
        .def("begin_end_frame", &Engine::beginEndFrame)
        .def("end_frame", &Engine::endFrame)
        .def("abort_frame", &Engine::abortFrame)
        .def_property_readonly(
            "frame_state", [](const Engine& e) { return std::string(Engine::toString(e.GetFrameState())); })
        .def_property_readonly("frame_count", &Engine::GetFrameCount)
        .def_property_readonly("fixed_delta_seconds",
                               [](const Engine& e) { return e.GetSettings().fixedDeltaSeconds; });
}
