// strata._strata: the pipeline for Python (the package strata wraps it, python/strata/).
//
// Options: the front-ends' one option table (strata::option_table, frontend/options.h: each
// option's CLI flag, Python keyword, library parameter, help and field of strata::Options, the
// Params structs) gives the keywords (keywords()). Python reads the defaults from it (a default-
// constructed Options), builds the functions' signatures from it and passes the keywords back
// as a dict; the same table translates library messages ("LayerParams::sweeps", "--sweeps")
// into keyword names. So no default, no name and no help is typed twice.
//
// Results: Mesh and Surface own the C++ mesh; their arrays are NumPy views into it (read-only,
// kept alive by the object), the report a dict.
//
// Errors: strata::InputError -> strata.InputError (also a ValueError), TopologyError,
// BackendError, other strata::Error -> strata.Error (a RuntimeError); strata::Cancelled ->
// strata.Cancelled (a KeyboardInterrupt) or the exception the progress callback raised.
//
// The GIL is held throughout: the progress hook runs Python (the callback, PyErr_CheckSignals
// for Ctrl-C) on the calling thread, and Gmsh (shared with Python's gmsh module) is not
// thread-safe anyway. Hooks called on other threads (OpenMP workers polling cancelled()) only
// read an atomic flag.

#include <strata/core/error.h>
#include <strata/core/progress.h>
#include <strata/core/validate.h>
#include <strata/frontend/options.h>
#include <strata/frontend/pipeline.h>
#include <strata/frontend/report.h>
#include <strata/geometry/check.h>
#include <strata/gmsh_api/gmsh_api.h>
#include <strata/hybrid/hybrid_mesh.h>
#include <strata/io/files.h>
#include <strata/io/formats.h>
#include <strata/io/geo_script.h>
#include <strata/io/gmsh_session.h>
#include <strata/io/write_report.h>
#include <strata/io/write_surface.h>
#include <strata/io/write_volume.h>
#include <strata/module/layers.h>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <cstring>
#include <functional>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace py = pybind11;
using namespace pybind11::literals;

namespace strata {
namespace {

static_assert(sizeof(Vec3) == 3 * sizeof(double), "points are viewed as one #nodes x 3 array");

// ---------------------------------------------------------------------------------------
// Options

/// Which functions take a keyword (bit mask).
enum Takes : int { kSurface = 1, kLayers = 2, kMesh = 4, kGmshModel = 8 };

struct Keyword {
    std::string name;   ///< the Python keyword
    std::string param;  ///< the library parameter it sets ("LayerParams::sweeps"), or "" for a front-end switch
    int takes = 0;      ///< Takes bits
    std::string doc;
    std::function<py::object(const Options&)> get;
    std::function<void(Options&, py::handle)> set;
};

/// A keyword bound to one field (\p field: Options& -> T&); Python values are cast to T.
template <class T>
void bind(Keyword& k, T& (*field)(Options&)) {
    k.get = [field](const Options& o) { return py::cast(field(const_cast<Options&>(o))); };
    k.set = [field, name = k.name](Options& o, py::handle v) {
        try {
            field(o) = v.cast<T>();
        } catch (const py::cast_error&) {
            throw py::type_error(name + "=" + py::repr(v).cast<std::string>() + ": expected " + py::type_id<T>());
        }
    };
}

/// A keyword that is None (off) or a size >= 0 (0: automatic), stored in \p field as a
/// negative number for off (OptionSpec::optional_size).
void optional_size(Keyword& k, double& (*field)(Options&)) {
    k.get = [field](const Options& o) -> py::object {
        const double size = field(const_cast<Options&>(o));
        if (size < 0.0) return py::none();
        return py::float_(size);
    };
    k.set = [field, name = k.name](Options& o, py::handle v) {
        if (v.is_none()) {
            field(o) = -1.0;
            return;
        }
        const double size = v.cast<double>();
        if (!(size >= 0.0))
            throw InputError(name + "=" + py::repr(v).cast<std::string>() +
                             ": expected None or a size >= 0 (0: automatic)");
        field(o) = size;
    };
}

/// The front-ends' option table (frontend/options.h) as keywords: its flags in the help named
/// as keywords; remesh and wrap are None or a size, patches None or a dict.
const std::vector<Keyword>& keywords() {
    static const std::vector<Keyword> table = [] {
        std::vector<Keyword> t;
        for (const OptionSpec& spec : option_table()) {
            if (spec.keyword.empty()) continue;
            int takes = 0;
            switch (spec.stage) {
                case OptionStage::Surface:
                    takes = kSurface | kLayers | kMesh;
                    break;
                case OptionStage::Patches:
                    takes = kSurface | kLayers | kMesh | kGmshModel;
                    break;
                case OptionStage::Layers:
                    takes = kLayers | kMesh | kGmshModel;
                    break;
                case OptionStage::Mesh:
                    takes = kMesh | kGmshModel;
                    break;
                case OptionStage::Output:  // with output=: a Gmsh model's mesh stays in Gmsh
                    takes = kLayers | kMesh;
                    break;
            }
            Keyword k{spec.keyword,
                      spec.param,
                      takes,
                      spec.keyword_help.empty() ? translate_names(spec.help, keyword_of_name()) : spec.keyword_help,
                      {},
                      {}};
            std::visit([&k](auto field) { bind(k, field); }, spec.field);
            if (spec.optional_size) {
                optional_size(k, std::get<double& (*)(Options&)>(spec.field));
            } else if (spec.keyword == "patches") {
                k.get = [](const Options& o) -> py::object {
                    if (o.surface.patches.empty()) return py::none();
                    py::dict d;
                    (void)parse_patch_options(o.surface.patches);  // checked
                    for (const std::string& item : o.surface.patches) {
                        const auto eq = item.rfind('=');
                        d[py::str(item.substr(0, eq))] = item.substr(eq + 1);
                    }
                    return py::object(std::move(d));
                };
                k.set = [](Options& o, py::handle v) {
                    o.surface.patches.clear();
                    if (v.is_none()) return;
                    if (!py::isinstance<py::dict>(v))
                        throw py::type_error("patches=" + py::repr(v).cast<std::string>() +
                                             ": expected a dict {patch name: kind}");
                    for (const auto& [name, kind] : v.cast<py::dict>())
                        o.surface.patches.push_back(py::str(name).cast<std::string>() + "=" +
                                                    py::str(kind).cast<std::string>());
                };
            }
            t.push_back(std::move(k));
        }
        return t;
    }();
    return table;
}

/// Options from a dict of keywords (Python checked the names; unknown ones are a TypeError here too).
Options options_from(const py::dict& kwargs) {
    Options o;
    for (const auto& [key, value] : kwargs) {
        const std::string name = py::str(key);
        bool found = false;
        for (const Keyword& k : keywords()) {
            if (k.name != name) continue;
            k.set(o, value);
            found = true;
            break;
        }
        if (!found) throw py::type_error("unknown keyword '" + name + "'");
    }
    return o;
}

// ---------------------------------------------------------------------------------------
// Errors

PyObject* g_error = nullptr;
PyObject* g_input_error = nullptr;
PyObject* g_topology_error = nullptr;
PyObject* g_backend_error = nullptr;
PyObject* g_output_error = nullptr;
PyObject* g_cancelled = nullptr;

/// Progress for Python: calls the callback (stage, fraction), checks for Ctrl-C on the
/// calling thread and, with a timeout, raises TimeoutError once it has passed; an exception
/// from any of these is kept, the stage is cancelled and the exception re-raised by the
/// binding (rethrow_kept). cancelled() checks too, so the timeout also stops a stage between
/// its reports (TetGen's child process is killed within 0.1 s).
class PythonProgress : public Progress {
public:
    PythonProgress(py::object callback, const py::object& timeout)
        : callback_(std::move(callback)), thread_(std::this_thread::get_id()) {
        // Beyond 1e9 s (an infinite timeout among them) there is no limit: the clock's ticks
        // would overflow.
        if (!timeout.is_none() && timeout.cast<double>() < 1e9) {
            timeout_text_ = py::str(py::repr(timeout));
            deadline_ =
                std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                                       std::chrono::duration<double>(timeout.cast<double>()));
        }
    }

    void report(std::string_view stage, double fraction) override {
        if (stop_.load() || std::this_thread::get_id() != thread_) return;
        stage_.assign(stage);
        try {
            if (!callback_.is_none()) callback_(py::str(stage.data(), stage.size()), fraction);
            check_signals();
            check_deadline();
        } catch (py::error_already_set& e) {
            keep(std::move(e));
        }
    }

    bool cancelled() const override {
        if (stop_.load()) return true;
        if (std::this_thread::get_id() != thread_) return false;
        // Between reports stages poll this in loops: look at signals every 50 ms at most.
        const auto now = std::chrono::steady_clock::now();
        if (now - last_check_ < std::chrono::milliseconds(50)) return false;
        last_check_ = now;
        try {
            check_signals();
            check_deadline();
        } catch (py::error_already_set& e) {
            keep(std::move(e));
        }
        return stop_.load();
    }

    /// Re-raise the kept exception (a KeyboardInterrupt from Ctrl-C as strata.Cancelled).
    [[noreturn]] void rethrow_kept() {
        if (kept_) {
            if (kept_->matches(PyExc_KeyboardInterrupt) && !kept_->matches(g_cancelled)) {
                kept_.reset();
                PyErr_SetString(g_cancelled, "cancelled by the user (Ctrl-C)");
                throw py::error_already_set();
            }
            py::error_already_set e = std::move(*kept_);
            kept_.reset();
            throw e;
        }
        PyErr_SetString(g_cancelled, "cancelled by the user");
        throw py::error_already_set();
    }

private:
    static void check_signals() {
        if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    }
    void check_deadline() const {
        if (!deadline_ || std::chrono::steady_clock::now() <= *deadline_) return;
        const std::string message = "stopped by timeout=" + timeout_text_ + " s in stage " +
                                    (stage_.empty() ? std::string("surface") : stage_) + "; nothing was written";
        PyErr_SetString(PyExc_TimeoutError, message.c_str());
        throw py::error_already_set();
    }
    void keep(py::error_already_set&& e) const {
        if (!kept_) kept_.emplace(std::move(e));
        stop_.store(true);
    }

    py::object callback_;
    std::thread::id thread_;
    std::optional<std::chrono::steady_clock::time_point> deadline_;  ///< none: no timeout
    std::string timeout_text_;                                       ///< the timeout as given, for the message
    std::string stage_;                                              ///< the stage last reported
    mutable std::atomic<bool> stop_{false};
    mutable std::optional<py::error_already_set> kept_;
    mutable std::chrono::steady_clock::time_point last_check_{};
};

/// Run \p f with a PythonProgress; C++ exceptions become Strata's Python exceptions with
/// the message's parameter names in keywords.
template <class F>
auto with_progress(const py::object& callback, const py::object& timeout, F&& f)
    -> decltype(f(std::declval<Progress*>())) {
    PythonProgress progress(callback, timeout);
    try {
        return f(&progress);
    } catch (const Cancelled&) {
        progress.rethrow_kept();
    }
}

void translate_exception(std::exception_ptr p) {
    auto raise = [](PyObject* type, const std::exception& e) {
        PyErr_SetString(type, translate_names(e.what(), keyword_of_name()).c_str());
    };
    try {
        if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
        raise(g_input_error, e);
    } catch (const TopologyError& e) {
        raise(g_topology_error, e);
    } catch (const BackendError& e) {
        raise(g_backend_error, e);
    } catch (const OutputError& e) {
        raise(g_output_error, e);
    } catch (const Error& e) {
        raise(g_error, e);
    } catch (const Cancelled& e) {
        PyErr_SetString(g_cancelled, e.what());
    }
}

// ---------------------------------------------------------------------------------------
// Results

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// A read-only NumPy view of \p rows x \p cols values at \p data, kept alive by \p owner.
template <class T>
py::array view(const T* data, std::size_t rows, std::size_t cols, py::handle owner) {
    py::array_t<T> a({rows, cols}, {cols * sizeof(T), sizeof(T)}, data, owner);
    py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
    return py::array(std::move(a));
}
template <class T>
py::array view(const std::vector<T>& v, py::handle owner) {
    py::array_t<T> a({v.size()}, {sizeof(T)}, v.data(), owner);
    py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
    return py::array(std::move(a));
}
template <class T, std::size_t N>
py::array view(const std::vector<std::array<T, N>>& v, py::handle owner) {
    return view(v.empty() ? nullptr : v.front().data(), v.size(), N, owner);
}
py::array points_view(const std::vector<Vec3>& points, py::handle owner) {
    return view(points.empty() ? nullptr : points.front().data(), points.size(), 3, owner);
}

/// Faces of \p boundary (all, or of patch \p patch) as {"triangle": (n, 3), "quad": (n, 4)} copies.
py::dict faces_of(const SurfaceMesh& boundary, std::optional<std::string> patch) {
    Index only = kNone;
    if (patch) {
        only = find_patch(boundary, *patch);
        if (only == kNone) {
            std::string names;
            for (const Patch& p : boundary.patches) names += (names.empty() ? "" : ", ") + p.name;
            throw InputError("no patch '" + *patch + "'; the patches are: " + names);
        }
    }
    std::vector<std::array<Index, 3>> tris;
    std::vector<std::array<Index, 4>> quads;
    for (Index f = 0; f < boundary.num_faces(); ++f) {
        if (only != kNone && boundary.face_patch[static_cast<std::size_t>(f)] != only) continue;
        const Index* n = boundary.face_begin(f);
        if (boundary.face_size(f) == 3)
            tris.push_back({n[0], n[1], n[2]});
        else
            quads.push_back({n[0], n[1], n[2], n[3]});
    }
    auto copy = [](const auto& cells, std::size_t width) {
        py::array_t<Index> a({cells.size(), width});
        if (!cells.empty()) std::memcpy(a.mutable_data(), cells.front().data(), cells.size() * width * sizeof(Index));
        return a;
    };
    return py::dict("triangle"_a = copy(tris, 3), "quad"_a = copy(quads, 4));
}

py::list patch_names(const SurfaceMesh& s) {
    py::list l;
    for (const Patch& p : s.patches) l.append(p.name);
    return l;
}
py::list patch_kinds(const SurfaceMesh& s) {
    py::list l;
    for (const Patch& p : s.patches) l.append(std::string(to_string(p.kind)));
    return l;
}

/// A report's value as Python's: a flag a bool, an integer an int, a number a float, a text a
/// str, a list a list, a node a dict in the node's order.
py::object to_python(const ReportValue& v) {
    switch (v.kind()) {
        case ReportValue::Kind::Flag:
            return py::bool_(v.flag());
        case ReportValue::Kind::Integer:
            return py::int_(v.integer());
        case ReportValue::Kind::Number:
            return py::float_(v.number());
        case ReportValue::Kind::Text:
            return py::str(v.text());
        case ReportValue::Kind::List: {
            py::list l;
            for (const ReportValue& e : v.list()) l.append(to_python(e));
            return l;
        }
        case ReportValue::Kind::Node: {
            py::dict d;
            for (const ReportNode::Entry& e : v.node().entries()) d[py::str(e.key)] = to_python(e.value);
            return d;
        }
    }
    return py::none();
}

/// The report tree (frontend/report.h) as a dict: the keys of OUT.report.json, and "times"'s
/// "write".
py::dict report_dict(const ReportNode& report) {
    return to_python(ReportValue(report));
}

/// A surface result: the oriented surface mesh with patches.
struct PySurface {
    SurfaceMesh mesh;
    py::dict report;
};

/// A volume result: the hybrid mesh (or the layers alone) and the report.
struct PyMesh {
    VolumeMesh mesh;
    py::dict report;
};

std::vector<std::string> as_inputs(const py::handle& input) {
    if (py::isinstance<py::str>(input) || py::hasattr(input, "__fspath__"))
        return {py::str(py::module_::import("os").attr("fspath")(input)).cast<std::string>()};
    std::vector<std::string> out;
    for (const py::handle item : input) out.push_back(py::str(py::module_::import("os").attr("fspath")(item)));
    return out;
}

/// The Python objects of a pipeline's \p r; \p write_seconds: writing its outputs took that.
py::object result_object(Result r, double write_seconds) {
    set_time(r.report, "write", write_seconds);
    if (r.job == Job::Surface) {
        auto result = std::make_unique<PySurface>();
        result->report = report_dict(r.report);
        result->mesh = std::move(r.surface);
        return py::cast(std::move(result));
    }
    auto result = std::make_unique<PyMesh>();
    result->report = report_dict(r.report);
    result->mesh = r.job == Job::Layers ? std::move(r.layers.mesh) : std::move(r.mesh);
    return py::cast(std::move(result));
}

/// surface(), layers() and mesh(): the pipeline's \p job on \p input with the keywords
/// \p kwargs; \p output, if given, checked before the work and written after it.
py::object run_job(Job job, const py::object& input, const py::dict& kwargs, const std::optional<std::string>& output,
                   const std::string& msh_version, bool binary, const py::object& callback,
                   const py::object& timeout) {
    Options o = options_from(kwargs);
    o.surface.inputs = as_inputs(input);
    if (o.surface.inputs.empty()) throw InputError("no input: give a CAD or surface-mesh file, or a list of them");
    o.surface.input = input_name(o.surface.inputs);
    const Request request = make_request(job, o);
    const MshFormat msh(parse_msh_version(msh_version), binary);
    if (o.output.foam_case && !output)
        throw InputError("OutputOptions::foam_case = true writes an OpenFOAM case: name its directory, "
                         "output=\"CASE\"");
    if (output) check_outputs(job, *output, msh, request.inputs, {}, o.output);
    return with_progress(callback, timeout, [&](Progress* progress) -> py::object {
        Result r = run(request, progress);
        const auto t = std::chrono::steady_clock::now();
        if (output) {
            OutputSet outputs;  // the mesh and its report, both or neither
            write_outputs(r, *output, msh, progress, outputs);
            outputs.commit();
        }
        return result_object(std::move(r), seconds_since(t));
    });
}

py::object run_surface(const py::object& input, const py::dict& kwargs, const std::optional<std::string>& output,
                       const std::string& msh_version, bool binary, const py::object& callback,
                       const py::object& timeout) {
    return run_job(Job::Surface, input, kwargs, output, msh_version, binary, callback, timeout);
}

py::object run_layers(const py::object& input, const py::dict& kwargs, const std::optional<std::string>& output,
                      const std::string& msh_version, bool binary, const py::object& callback,
                       const py::object& timeout) {
    return run_job(Job::Layers, input, kwargs, output, msh_version, binary, callback, timeout);
}

py::object run_mesh(const py::object& input, const py::dict& kwargs, const std::optional<std::string>& output,
                    const std::string& msh_version, bool binary, const py::object& callback,
                       const py::object& timeout) {
    return run_job(Job::Mesh, input, kwargs, output, msh_version, binary, callback, timeout);
}

py::dict run_gmsh_model(const py::dict& kwargs, const py::object& callback, const py::object& timeout) {
    Options o = options_from(kwargs);
    const HybridParams hp = hybrid_params(o.layers, o.mesh);
    PrepareParams pp = o.surface.prepare;  // patch kinds, internal flow, merge tolerance: what applies to a model
    pp.patch_kinds = parse_patch_options(o.surface.patches);
    pp.patch_names = parse_patch_renames(o.surface.patches);
    return with_progress(callback, timeout, [&](Progress* progress) {
        const auto t0 = std::chrono::steady_clock::now();
        FirstHeightChoice chosen;
        const HybridReport hr = mesh_current_gmsh_model(hp, pp, progress, &chosen);
        // The model's mesh is Gmsh's now: the report has its cells (from the validation) but not
        // its nodes or patch names.
        ReportNode report = mesh_run_report(nullptr, hr, nullptr, nullptr, o, {});
        if (chosen.automatic) report.set("automatic_first_height", first_height_report(chosen));
        set_time(report, "total", seconds_since(t0));
        py::dict d = report_dict(report);
        return d;
    });
}

/// Strata's exception types on the module \p m, and their translation from C++: one base,
/// InputError also a ValueError, OutputError also an OSError, Cancelled a KeyboardInterrupt.
void register_exceptions(py::module_& m) {
    g_error =
        PyErr_NewExceptionWithDoc("strata.Error", "Base of every error Strata raises.", PyExc_RuntimeError, nullptr);
    py::tuple input_bases = py::make_tuple(py::handle(g_error), py::handle(PyExc_ValueError));
    // The base may be a tuple: InputError is a ValueError as well.
    g_input_error = PyErr_NewExceptionWithDoc(
        "strata.InputError", "Unusable input: a missing or unreadable file, a bad format or option value.",
        input_bases.ptr(), nullptr);
    g_topology_error = PyErr_NewExceptionWithDoc(
        "strata.TopologyError", "Invalid mesh topology or geometry (non-manifold edge, inverted cell, ...).", g_error,
        nullptr);
    g_backend_error =
        PyErr_NewExceptionWithDoc("strata.BackendError", "Gmsh, OpenCASCADE or TetGen failed.", g_error, nullptr);
    py::tuple output_bases = py::make_tuple(py::handle(g_error), py::handle(PyExc_OSError));
    g_output_error = PyErr_NewExceptionWithDoc(
        "strata.OutputError",
        "An output could not be written to the end (disk full, quota, permission); the previous file is as it was.",
        output_bases.ptr(), nullptr);
    g_cancelled = PyErr_NewExceptionWithDoc("strata.Cancelled", "The run was cancelled (Ctrl-C); nothing was written.",
                                            PyExc_KeyboardInterrupt, nullptr);
    m.attr("Error") = py::handle(g_error);
    m.attr("InputError") = py::handle(g_input_error);
    m.attr("TopologyError") = py::handle(g_topology_error);
    m.attr("BackendError") = py::handle(g_backend_error);
    m.attr("OutputError") = py::handle(g_output_error);
    m.attr("Cancelled") = py::handle(g_cancelled);
    // The growth ratio geometric layers take when growth is 0 (DistributionParams::growth), for
    // panels that show it rather than its 0.
    m.attr("DEFAULT_GROWTH") = kDefaultGrowth;
    py::register_exception_translator(&translate_exception);
}

/// The class Surface: a surface result's arrays (views), report and writer.
void bind_surface(py::module_& m) {
    py::class_<PySurface>(m, "Surface", "A checked, oriented surface mesh with patches (strata.surface).")
        .def_property_readonly(
            "points", [](py::object self) { return points_view(self.cast<PySurface&>().mesh.points, self); },
            "#nodes x 3 float64, model units (read-only view)")
        .def_property_readonly(
            "face_offsets", [](py::object self) { return view(self.cast<PySurface&>().mesh.face_offsets, self); },
            "#faces + 1: face f is face_nodes[face_offsets[f]:face_offsets[f+1]]")
        .def_property_readonly(
            "face_nodes", [](py::object self) { return view(self.cast<PySurface&>().mesh.face_nodes, self); },
            "node ids, 3 or 4 per face")
        .def_property_readonly(
            "face_patch", [](py::object self) { return view(self.cast<PySurface&>().mesh.face_patch, self); },
            "#faces, index into patch_names")
        .def_property_readonly("patch_names", [](const PySurface& s) { return patch_names(s.mesh); })
        .def_property_readonly("patch_kinds", [](const PySurface& s) { return patch_kinds(s.mesh); })
        .def(
            "faces", [](const PySurface& s, std::optional<std::string> patch) { return faces_of(s.mesh, patch); },
            py::arg("patch") = py::none(), "{'triangle': (n, 3), 'quad': (n, 4)} node ids, of one patch or all")
        .def_readonly("report", &PySurface::report)
        .def(
            "write",
            [](const PySurface& s, const std::string& path, const std::string& msh_version, bool binary) {
                write_surface(s.mesh, path, MshFormat(parse_msh_version(msh_version), binary));
            },
            py::arg("path"), py::arg("msh_version") = "4.1", py::arg("binary") = false,
            "Write the surface (.msh, .vtk, .stl, ... by extension; binary: a binary .msh).")
        .def("__repr__", [](const PySurface& s) {
            return "<strata.Surface: " + std::to_string(s.mesh.num_points()) + " nodes, " +
                   std::to_string(s.mesh.num_faces()) + " faces, " + std::to_string(s.mesh.patches.size()) +
                   " patches>";
        });
}

/// The class Mesh: a volume result's arrays (views), report and writer.
void bind_mesh(py::module_& m) {
    auto cells = [](py::object self, CellType t) {
        const VolumeMesh& mesh = self.cast<PyMesh&>().mesh;
        return mesh.with_cells(t, [&](const auto& block) { return view(block, self); });
    };
    py::class_<PyMesh>(m, "Mesh", "A hybrid volume mesh (strata.mesh) or boundary layers (strata.layers).")
        .def_property_readonly(
            "points", [](py::object self) { return points_view(self.cast<PyMesh&>().mesh.points, self); },
            "#nodes x 3 float64, model units (read-only view)")
        .def_property_readonly(
            "tets", [cells](py::object self) { return cells(self, CellType::Tet); }, "#tetrahedra x 4 node ids")
        .def_property_readonly(
            "pyramids", [cells](py::object self) { return cells(self, CellType::Pyramid); },
            "#pyramids x 5 node ids (base 0-1-2-3, apex 4)")
        .def_property_readonly(
            "prisms", [cells](py::object self) { return cells(self, CellType::Prism); },
            "#prisms x 6 node ids (bottom 0-1-2, top 3-4-5)")
        .def_property_readonly(
            "hexes", [cells](py::object self) { return cells(self, CellType::Hex); },
            "#hexahedra x 8 node ids (bottom 0-1-2-3, top 4-5-6-7)")
        .def_property_readonly(
            "cells",
            [cells](py::object self) {
                py::dict d;
                for (const CellType t : kCellTypes) d[py::str(std::string(to_string(t)))] = cells(self, t);
                return d;
            },
            "{'tetrahedron': (n, 4), 'pyramid': (n, 5), 'prism': (n, 6), 'hexahedron': (n, 8)} views")
        .def_property_readonly(
            "face_offsets", [](py::object self) { return view(self.cast<PyMesh&>().mesh.boundary.face_offsets, self); },
            "boundary faces, CSR: #faces + 1 offsets into face_nodes")
        .def_property_readonly(
            "face_nodes", [](py::object self) { return view(self.cast<PyMesh&>().mesh.boundary.face_nodes, self); },
            "boundary faces' node ids, 3 or 4 per face, normals out of the domain")
        .def_property_readonly(
            "face_patch", [](py::object self) { return view(self.cast<PyMesh&>().mesh.boundary.face_patch, self); },
            "#boundary faces, index into patch_names")
        .def_property_readonly("patch_names", [](const PyMesh& s) { return patch_names(s.mesh.boundary); })
        .def_property_readonly("patch_kinds", [](const PyMesh& s) { return patch_kinds(s.mesh.boundary); })
        .def(
            "faces", [](const PyMesh& s, std::optional<std::string> patch) { return faces_of(s.mesh.boundary, patch); },
            py::arg("patch") = py::none(), "boundary faces {'triangle': (n, 3), 'quad': (n, 4)}, of one patch or all")
        .def_readonly("report", &PyMesh::report)
        .def(
            "write",
            [](const PyMesh& s, const std::string& path, const std::string& msh_version, bool binary) {
                write_volume(s.mesh, path, MshFormat(parse_msh_version(msh_version), binary));
            },
            py::arg("path"), py::arg("msh_version") = "4.1", py::arg("binary") = false,
            "Write the mesh (.cgr with its .bc map, .msh, .vtk, .su2, ... by extension; binary: a binary .msh).")
        .def("__repr__", [](const PyMesh& s) {
            return "<strata.Mesh: " + std::to_string(s.mesh.points.size()) + " nodes, " +
                   std::to_string(s.mesh.tets.size()) + " tetrahedra, " + std::to_string(s.mesh.pyramids.size()) +
                   " pyramids, " + std::to_string(s.mesh.prisms.size()) + " prisms, " +
                   std::to_string(s.mesh.hexes.size()) + " hexahedra>";
        });
}

}  // namespace
}  // namespace strata

PYBIND11_MODULE(_strata, m) {
    using namespace strata;
    m.doc() = "Strata's C++ pipeline; use the package strata (strata.mesh, strata.layers, strata.surface).";

    register_exceptions(m);

    m.def(
        "keywords",
        [] {
            const Options defaults;
            py::list l;
            for (const Keyword& k : keywords()) {
                py::list takes;
                if (k.takes & kSurface) takes.append("surface");
                if (k.takes & kLayers) takes.append("layers");
                if (k.takes & kMesh) takes.append("mesh");
                if (k.takes & kGmshModel) takes.append("gmsh");
                l.append(py::dict("name"_a = k.name, "default"_a = k.get(defaults), "param"_a = k.param,
                                  "takes"_a = takes, "doc"_a = k.doc));
            }
            return l;
        },
        "The keywords of surface(), layers(), mesh() and gmsh.mesh_current_model(): name, default (from a "
        "default-constructed Params struct), the library parameter it sets, which functions take it, and a line "
        "of help.");
    m.def(
        "translate", [](const std::string& message) { return translate_names(message, keyword_of_name()); },
        "A library message with its parameter names and CLI flags in Python keywords.");

    bind_surface(m);
    bind_mesh(m);

    const char* run_doc = "(input, options: dict, output, msh_version, binary, progress, timeout); see strata.";
    m.def("check_geo_script", &check_geo_script, py::arg("path"),
          "Raise InputError if the .geo script at path (or one it Includes or Merges) runs commands or writes "
          "files, naming the line.");
    m.def("surface", &run_surface, py::arg("input"), py::arg("options"), py::arg("output"), py::arg("msh_version"),
          py::arg("binary"), py::arg("progress"), py::arg("timeout"), run_doc);
    m.def("layers", &run_layers, py::arg("input"), py::arg("options"), py::arg("output"), py::arg("msh_version"),
          py::arg("binary"), py::arg("progress"), py::arg("timeout"), run_doc);
    m.def("mesh", &run_mesh, py::arg("input"), py::arg("options"), py::arg("output"), py::arg("msh_version"),
          py::arg("binary"), py::arg("progress"), py::arg("timeout"), run_doc);
    m.def("mesh_current_gmsh_model", &run_gmsh_model, py::arg("options"), py::arg("progress"), py::arg("timeout"),
          "strata::mesh_current_gmsh_model on the current Gmsh model; returns the report dict.");
    m.def(
        "note_gmsh_user",
        [] {
            // GmshLock records that the user initialised Gmsh (here: Python's gmsh module), so
            // that Strata's readers neither initialise Gmsh again nor finalise it under the user.
            try {
                GmshLock lock("strata");
            } catch (const InputError&) {
                return false;
            }
            return true;
        },
        "True if Gmsh is initialised (by Python's gmsh module); Strata then leaves it initialised.");
}
