// The in-process engine module, spear._spear_engine: the generated bindings of every engine class,
// the frame loop, and the dynamic API.

#include <dlfcn.h>

#include <cstdio>
#include <cstring>
#include <filesystem>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <pybind11/stl.h>

#include "core/base/asset_path.h"
#include "core/base/log.h"
#include "core/base/process_memory.h"
#include "core/base/progress.h"
#include "core/engine/engine.h"
#include "core/imageio/exr.h"
#include "core/plugin/plugin_loader.h"
#include "core/pybind/bridge.h"
#include "core/pybind/dynamic_access.h"
#include "core/pybind/errors.h"
#include "core/pybind/object_ref.h"
#include "core/pybind/value_convert.h"
#include "core/rpc/server.h"
#include "core/spfunc/sp_func_call.h"
#include "core/world/object_access.h"

namespace py = pybind11;

void spear_bind_engine(py::module_& m);

namespace {
void checkFrame(sp::reflect::ObjectBase& object, std::string_view context) {
    sp::world::checkObjectAccess(object, context);
}

bool pythonFinalizing() {
#if PY_VERSION_HEX >= 0x030D0000
    return Py_IsFinalizing();
#else
    return _Py_IsFinalizing();
#endif
}

// A Python error raised while showing a log line or progress is not the engine's to handle: Ctrl-C (a
// KeyboardInterrupt, raised by the signal handler that runs during the call) is raised again at the next
// chance Python gets; anything else is reported as unraisable.
void setAside(py::error_already_set& error, const char* what) {
    if (error.matches(PyExc_KeyboardInterrupt))
        PyErr_SetInterrupt();
    else
        error.discard_as_unraisable(what);
}

// Calls spear's Python function `module.name` from any engine thread, under the GIL; false while Python
// shuts down or when the call raised (set aside as above). `function` caches the function; it is never
// freed: no Python object may be released after the interpreter is gone.
template <typename... Args>
bool callPython(py::object*& function, const char* module, const char* name, const char* what,
                const Args&... args) {
    if (!Py_IsInitialized() || pythonFinalizing())
        return false;
    py::gil_scoped_acquire gil;
    try {
        if (!function)
            function = new py::object(py::module_::import(module).attr(name));
        (*function)(args...);
        return true;
    } catch (py::error_already_set& error) {
        setAside(error, what);
        return false;
    }
}

// Engine log lines become Python logging records (spear._logging.emit), from any thread. While Python
// shuts down, or if the logging call fails, the line goes to stderr as it would without a sink.
void logToPython(std::string_view file, int line, std::string_view message) {
    static py::object* emit = nullptr;
    if (!callPython(emit, "spear._logging", "emit", "spear: routing an engine log line to logging", file,
                    line, message))
        std::fprintf(stderr, "[spear] %.*s:%d: %.*s\n", int(file.size()), file.data(), line,
                     int(message.size()), message.data());
}

// Progress reports of long engine work become terminal bars and end-of-task records (spear._progress).
void progressToPython(std::string_view task, double done, double total, bool finished) {
    static py::object* report = nullptr;
    callPython(report, "spear._progress", "report", "spear: showing the engine's progress", task, done, total,
               finished);
}

// SpFuncs, in-process: arrays pass as views of the numpy buffers and come back as arrays that own the
// C++ storage; spear._spfunc checks the bundle and handles the JSON of unreal_objs for both transports.
py::dict callSpFunc(py::handle uobject, const std::string& name, const py::dict& arrays,
                    std::map<std::string, std::string> unrealObjs, std::string info,
                    const std::string& context) {
    sp::reflect::ObjectBase& object = sp::pybind::resolveArgument(uobject, context);
    SpFuncDataBundle args;
    for (auto [key, array] : arrays) {
        const std::string name = key.cast<std::string>();
        sp::reflect::Value value = sp::pybind::toValue(array, context + ": arrays['" + name + "']");
        args.packed_arrays_.emplace(name, std::move(value.as<sp::reflect::ArrayValue>()));
    }
    args.unreal_obj_strings_ = std::move(unrealObjs);
    args.info_ = std::move(info);
    SpFuncDataBundle result = sp::spfunc::call(object, name, std::move(args));
    py::dict resultArrays;
    for (const auto& [key, array] : result.packed_arrays_)
        resultArrays[py::str(key)] = sp::pybind::arrayToNumpy(array);
    py::dict out;
    out["arrays"] = resultArrays;
    out["unreal_objs"] = py::cast(result.unreal_obj_strings_);
    out["info"] = py::str(result.info_);
    return out;
}
// An EXR file as the array read_pixels() gives for its modality: (H, W) for one channel, else (H, W, C).
py::array readExr(const std::string& path) {
    py::gil_scoped_release release;
    sp::imageio::Image image = sp::imageio::readExr(path, "spear.images.read_exr()");
    py::gil_scoped_acquire acquire;
    std::vector<py::ssize_t> shape{image.height, image.width};
    if (image.channelNames.size() > 1)
        shape.push_back(py::ssize_t(image.channelNames.size()));
    py::array array(py::dtype(sp::imageio::toString(image.type)), shape);
    std::memcpy(array.mutable_data(), image.pixels.data(), image.pixels.size());
    return array;
}
} // namespace

PYBIND11_MODULE(_spear_engine, m) {
    m.doc() = "spear's in-process engine (generated bindings; use the spear package, not this module)";
    sp::pybind::registerErrorTranslator();
    sp::base::setLogSink(&logToPython);
    sp::base::setProgressSink(&progressToPython);
    // Built-in assets: beside an installed package (spear/assets), else the checkout the module was built
    // from.
    // (__file__ is set only after this function: the module's own file comes from the dynamic loader.)
    Dl_info self{};
    if (dladdr(reinterpret_cast<void*>(&checkFrame), &self) && self.dli_fname)
        sp::useBuiltinAssetsOf(std::filesystem::path(self.dli_fname).parent_path());
    sp::pybind::setAccessCheck(&checkFrame);
    spear_bind_engine(m);
    sp::pybind::bindDynamicAccess(m, "spear._engine.api");
    m.def(
        "_load_plugin",
        [](const std::string& path, const std::string& apiHash) {
            const auto& info = sp::plugin::load(path, apiHash);
            return py::make_tuple(info.name, info.classes);
        },
        py::arg("path"), py::arg("api_hash"), "Loads a plugin library (use Instance.load_plugin()).");
    m.def("_unload_plugin", &sp::plugin::unload, py::arg("name"),
          "Unloads a plugin's classes (use Instance.unload_plugin()).");
    m.def("_read_exr", &readExr, py::arg("path"), "Reads an EXR file (use spear.images.read_exr()).");
    m.def("_call_sp_func", &callSpFunc, "Calls an SpFunc (use obj.call_sp_func()).");
    m.def(
        "_get_sp_func_names",
        [](py::handle uobject, const std::string& context) {
            return sp::spfunc::funcNames(sp::pybind::resolveArgument(uobject, context));
        },
        "The SpFuncs of an object (use obj.get_sp_func_names()).");

    using sp::engine::Engine;
    py::class_<Engine>(m, "Engine", "The engine: its worlds and the frame loop.")
        .def(py::init([](double fixedDeltaSeconds, bool editor, std::string scene) {
                 // The same allocator settings as spear-server's (core/base/process_memory.h): the Python
                 // process that runs an engine is a simulator's process; the environment's MALLOC_*
                 // thresholds, when set, win.
                 sp::keepFreedMemory();
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
        .def(
            "create_world",
            [](Engine& e, const std::string& name) { return sp::pybind::wrapObject(&e.CreateWorld(name)); },
            py::arg("name"))
        .def(
            "destroy_world",
            [](Engine& e, py::handle world) {
                // Like create_world, any time the engine is not ticking: no frame needed.
                auto* target = dynamic_cast<UWorld*>(&sp::pybind::resolveHandle(world, "destroy_world()"));
                SP_CHECK(target, sp::InvalidArgument, "destroy_world(): 'world' is not a world");
                e.DestroyWorld(*target);
            },
            py::arg("world"))
        .def("get_worlds",
             [](const Engine& e) {
                 py::list worlds;
                 for (UWorld* world : e.GetWorlds())
                     worlds.append(sp::pybind::wrapObject(world));
                 return worlds;
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

    // The browser inspector of an in-process engine: spear-server's Server with no main port, pumped by
    // Instance between frames (the engine's thread is Python's: nothing else may touch the engine).
    using sp::rpc::Server;
    py::class_<Server>(m, "InspectorServer",
                       "The browser inspector of an in-process engine (use Instance.inspect()).")
        .def(py::init([](Engine& engine, int port, std::string root, std::string apiHash) {
                 sp::rpc::ServerOptions options;
                 options.inspectPort = port;
                 options.inspectRoot = std::move(root);
                 return std::make_unique<Server>(engine, std::move(options), std::move(apiHash));
             }),
             py::arg("engine"), py::arg("port"), py::arg("root"), py::arg("api_hash"), py::keep_alive<1, 2>())
        .def_property_readonly("url", &Server::inspectUrl)
        .def("open", &Server::openInspector, py::arg("port"))
        // Pumped with the GIL held: the engine is Python's, and another Python thread must not call into it
        // meanwhile. Waiting for a browser releases it.
        .def(
            "pump", [](Server& server) { server.pump(0); }, "Answers what the inspector's browsers sent.")
        .def("wait_ready", &Server::waitReady, py::arg("timeout_ms"),
             "Whether a browser sent something, waiting up to timeout_ms.",
             py::call_guard<py::gil_scoped_release>());
}
