// A ready-to-run OpenFOAM case round Strata's polyMesh (openfoam_case.h).
//
// The numerics are those that run on Strata's meshes as they are (prism layers, then
// tetrahedra up to about 65 degrees of non-orthogonality): limited gradients and Laplacians,
// one non-orthogonal corrector, SIMPLE with under-relaxation, first-order upwind convection for
// a robust start (tests/openfoam/run_simplefoam.sh runs them and requires the residuals to fall
// by two orders). On the hemisphere-cylinder half model, linearUpwind for U at the start left
// p's residual wandering round 1e-2 and unlimited gradients of k and omega diverged; the
// comment in fvSchemes says how to switch to second order once the start has converged.
//
// Wall functions on every wall: in OpenFOAM v1912 omegaWallFunction switches between its
// viscous-sublayer and log-layer values by y+ and nutkWallFunction gives no eddy viscosity
// below y+ 11, so the same conditions hold for layers whose first cell is at y+ 1 (they act as
// low-Re conditions there) and for those at 30 to 300.

#include <strata/core/error.h>
#include <strata/core/format.h>
#include <strata/io/openfoam_case.h>

#include "foam_dictionary.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>

namespace strata {

namespace fs = std::filesystem;

namespace {

/// The initial fields, in the order written; each a file of 0.orig/ and of 0/.
constexpr std::array<const char*, 5> kFields = {"U", "p", "k", "omega", "nut"};

/// The case's files besides the fields.
constexpr std::array<const char*, 5> kDictionaries = {"system/controlDict", "system/fvSchemes", "system/fvSolution",
                                                      "constant/transportProperties", "constant/turbulenceProperties"};

/// What a patch is to the flow: its kind, and for kind other what its name says.
enum class Role { Wall, Farfield, Symmetry, Inlet, Outlet, Open };

Role role_of(const PolyPatch& p) {
    switch (p.kind) {
        case PatchKind::Wall:
            return Role::Wall;
        case PatchKind::Farfield:
            return Role::Farfield;
        case PatchKind::Symmetry:
            return Role::Symmetry;
        case PatchKind::Other:
            break;
    }
    std::string name = p.name;
    std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::tolower(c); });
    if (name.find("inlet") != std::string::npos || name.find("inflow") != std::string::npos) return Role::Inlet;
    if (name.find("outlet") != std::string::npos || name.find("outflow") != std::string::npos) return Role::Outlet;
    return Role::Open;
}

/// The conditions of one role: a comment, then each field's entries ("type; key value; ...").
struct Conditions {
    const char* comment;
    std::array<const char*, kFields.size()> entries;  ///< U, p, k, omega, nut
};

const Conditions& conditions(Role role) {
    static const std::array<Conditions, 6> table = {{
        {"wall: no slip, wall functions (right from y+ 1 to 300 in v1912)",
         {"noSlip", "zeroGradient", "kqRWallFunction; value uniform $kinf",
          "omegaWallFunction; value uniform $omegainf", "nutkWallFunction; value uniform 0"}},
        {"farfield: the freestream where the flow enters, zero gradient where it leaves",
         {"freestreamVelocity; freestreamValue uniform $Uinf", "freestreamPressure; freestreamValue uniform 0",
          "inletOutlet; inletValue uniform $kinf; value uniform $kinf",
          "inletOutlet; inletValue uniform $omegainf; value uniform $omegainf", "calculated; value uniform 0"}},
        {"symmetry plane", {"symmetry", "symmetry", "symmetry", "symmetry", "symmetry"}},
        {"inlet (kind other, named so): the freestream speed along the inward normal, freestream turbulence",
         {"surfaceNormalFixedValue; refValue uniform $Uin; value uniform $Uinf", "zeroGradient",
          "fixedValue; value uniform $kinf", "fixedValue; value uniform $omegainf", "calculated; value uniform 0"}},
        {"outlet (kind other, named so): fixed pressure, no backflow",
         {"inletOutlet; inletValue uniform (0 0 0); value uniform $Uinf", "fixedValue; value uniform 0",
          "inletOutlet; inletValue uniform $kinf; value uniform $kinf",
          "inletOutlet; inletValue uniform $omegainf; value uniform $omegainf", "calculated; value uniform 0"}},
        {"kind other, its name saying neither inlet nor outlet: an outflow plane (fixed pressure, no\n"
         "    // backflow), as Strata's kind other means; for an inlet, name it so (--patch NAME=other:inlet)\n"
         "    // or write an inlet's conditions here",
         {"inletOutlet; inletValue uniform (0 0 0); value uniform $Uinf", "fixedValue; value uniform 0",
          "inletOutlet; inletValue uniform $kinf; value uniform $kinf",
          "inletOutlet; inletValue uniform $omegainf; value uniform $omegainf", "calculated; value uniform 0"}},
    }};
    return table[static_cast<std::size_t>(role)];
}

/// "    key             value;\n" for each "key value" of \p entries ("type" first, implied).
std::string entry_lines(const std::string& entries) {
    std::string out;
    std::size_t at = 0;
    bool first = true;
    while (at < entries.size()) {
        std::size_t end = entries.find("; ", at);
        if (end == std::string::npos) end = entries.size();
        std::string item = entries.substr(at, end - at);
        if (first) item = "type " + item;
        first = false;
        const std::size_t space = item.find(' ');
        std::string key = item.substr(0, space);
        key.resize(std::max<std::size_t>(key.size() + 1, 16), ' ');
        out += "        " + key + item.substr(space + 1) + ";\n";
        at = end + 2;
    }
    return out;
}

std::string number(double v) {
    return format_number(v, 10);
}

std::string vector_text(const Vec3& v) {
    return "(" + number(v.x()) + " " + number(v.y()) + " " + number(v.z()) + ")";
}

double k_freestream(const FoamCaseParams& p) {
    const double u = p.turbulence_intensity * p.velocity.norm();
    return 1.5 * u * u;
}

double omega_freestream(const FoamCaseParams& p) {
    return k_freestream(p) / (foam_viscosity(p) * p.viscosity_ratio);
}

/// "NAME value; // comment" lines at the head of a field, aligned as OpenFOAM writes entries.
std::string variable(std::string name, const std::string& value, const std::string& comment) {
    name.resize(std::max<std::size_t>(name.size() + 1, 16), ' ');
    return name + value + ";  // " + comment + "\n";
}

/// One initial field (\p index in kFields) with an entry per patch.
std::string field_file(std::size_t index, const std::vector<PolyPatch>& patches, const FoamCaseParams& p) {
    const std::string name = kFields[index];
    const bool vector = name == "U";
    std::string s = foam_header(vector ? "volVectorField" : "volScalarField", "0", name);
    s += "// Strata wrote this field into 0.orig/ with the mesh; 0/ is a copy of 0.orig/ made anew each time the\n"
         "// mesh is written (potentialFoam and simpleFoam write into 0/): edit 0.orig/.\n\n";
    const bool inlet =
        std::any_of(patches.begin(), patches.end(), [](const PolyPatch& q) { return role_of(q) == Role::Inlet; });
    std::string dimensions = "[0 2 -2 0 0 0 0]", internal = "0";
    if (name == "U") {
        s += variable("Uinf", vector_text(p.velocity), "the freestream velocity, model units per second");
        if (inlet) s += variable("Uin", number(-p.velocity.norm()), "the inlets' normal velocity: -|Uinf|, inward");
        dimensions = "[0 1 -1 0 0 0 0]", internal = "$Uinf";
    } else if (name == "k") {
        s += variable("kinf", number(k_freestream(p)),
                      "1.5 (I |Uinf|)^2, turbulence intensity I = " + number(p.turbulence_intensity));
        internal = "$kinf";
    } else if (name == "omega") {
        s += variable("omegainf", number(omega_freestream(p)),
                      "kinf / (nu nut/nu), eddy-viscosity ratio nut/nu = " + number(p.viscosity_ratio));
        dimensions = "[0 0 -1 0 0 0 0]", internal = "$omegainf";
    } else if (name == "nut") {
        dimensions = "[0 2 -1 0 0 0 0]";
    }
    s += "\ndimensions      " + dimensions + ";\n\ninternalField   uniform " + internal + ";\n\nboundaryField\n{\n";
    for (const PolyPatch& q : patches) {
        const Conditions& c = conditions(role_of(q));
        s += "    // " + std::string(c.comment) + "\n    " + q.name + "\n    {\n" + entry_lines(c.entries[index]) +
             "    }\n";
    }
    s += "}\n\n";
    s += kFoamFooter;
    return s;
}

/// What every file of system/ and constant/ says of the flow and the mesh.
std::string flow_comment(const FoamCaseParams& p) {
    std::string s = "// The flow: Uinf = " + vector_text(p.velocity) +
                    " (0.orig/U), nu = " + number(foam_viscosity(p)) +
                    " (constant/transportProperties):\n// Re = |Uinf| L / nu = " + number(p.reynolds) +
                    " on the reference length L = " + number(p.reference_length) +
                    ". Lengths are the mesh's units, which OpenFOAM takes\n// for metres: the Reynolds number holds "
                    "whatever the unit.";
    if (p.first_height > 0.0) {
        s += " First layer height " + number(p.first_height);
        if (p.yplus > 0.0) s += ": y+ about " + format_number(p.yplus, 3) + " (flat plate, Cf = 0.026 Re^-1/7)";
        s += ".";
    }
    return s +
           "\n// Strata writes each file of system/, constant/ and 0.orig/ only where the case has none: edit "
           "them.\n\n";
}

/// A dictionary of system/ or constant/: its header, \p intro, what it says of the flow, \p body.
std::string dictionary(const char* location, const char* object, const FoamCaseParams& p, const std::string& body,
                       const std::string& intro = "") {
    return foam_header("dictionary", location, object) + intro + flow_comment(p) + body + std::string(kFoamFooter);
}

std::string control_dict(const FoamCaseParams& p) {
    return dictionary(
        "system", "controlDict", p,
        "application     simpleFoam;\n\nstartFrom       startTime;\n\nstartTime       0;\n\n"
        "stopAt          endTime;\n\nendTime         " +
            std::to_string(p.iterations) +
            ";\n\ndeltaT          1;\n\nwriteControl    timeStep;\n\nwriteInterval   100;\n\n"
            "purgeWrite      0;\n\nwriteFormat     ascii;\n\nwritePrecision  8;\n\nwriteCompression off;\n\n"
            "timeFormat      general;\n\ntimePrecision   6;\n\nrunTimeModifiable true;\n\n"
            "functions\n{\n    // y+ of the first cells on the walls, at each write (postProcessing/yPlus)\n"
            "    yPlus\n    {\n        type            yPlus;\n"
            "        libs            (\"libfieldFunctionObjects.so\");\n        writeControl    writeTime;\n    "
            "}\n}\n\n",
        "// A steady incompressible RANS start, written by Strata with the mesh (constant/polyMesh):\n"
        "//   potentialFoam -case CASE   a potential flow in 0/U to start from (optional)\n"
        "//   simpleFoam -case CASE      k-omega SST to endTime, or sooner where residualControl (fvSolution) is "
        "met\n");
}

std::string fv_schemes(const FoamCaseParams& p) {
    return dictionary("system", "fvSchemes", p,
                      "ddtSchemes\n{\n    default         steadyState;\n}\n\n"
                      "// Limited: the tetrahedra's and the thin layer cells' gradients (unlimited gradients of k and "
                      "omega\n// diverged on Strata's meshes)\n"
                      "gradSchemes\n{\n    default         cellLimited Gauss linear 1;\n}\n\n"
                      "divSchemes\n{\n    default         none;\n"
                      "    // First order for a robust start; once it has converged, second order for U:\n"
                      "    //     div(phi,U)      bounded Gauss linearUpwind grad(U);\n"
                      "    div(phi,U)      bounded Gauss upwind;\n"
                      "    div(phi,k)      bounded Gauss upwind;\n    div(phi,omega)  bounded Gauss upwind;\n"
                      "    div((nuEff*dev2(T(grad(U))))) Gauss linear;\n}\n\n"
                      "laplacianSchemes\n{\n    default         Gauss linear limited corrected 0.5;\n}\n\n"
                      "interpolationSchemes\n{\n    default         linear;\n}\n\n"
                      "snGradSchemes\n{\n    default         limited corrected 0.5;\n}\n\n"
                      "wallDist\n{\n    method          meshWave;\n}\n\n");
}

std::string fv_solution(const FoamCaseParams& p) {
    return dictionary(
        "system", "fvSolution", p,
        "solvers\n{\n"
        "    p\n    {\n        solver          GAMG;\n        smoother        GaussSeidel;\n"
        "        tolerance       1e-07;\n        relTol          0.05;\n    }\n\n"
        "    // potentialFoam's potential\n    Phi\n    {\n        $p;\n        tolerance       1e-08;\n"
        "        relTol          0;\n    }\n\n"
        "    \"(U|k|omega)\"\n    {\n        solver          smoothSolver;\n        smoother        symGaussSeidel;\n"
        "        tolerance       1e-08;\n        relTol          0.1;\n    }\n}\n\n"
        "SIMPLE\n{\n    // one corrector for the tetrahedra's non-orthogonality (up to about 65 degrees)\n"
        "    nNonOrthogonalCorrectors 1;\n    consistent      no;\n\n"
        "    // simpleFoam stops here before endTime\n    residualControl\n    {\n        p               1e-04;\n"
        "        U               1e-05;\n        \"(k|omega)\"     1e-05;\n    }\n}\n\n"
        "potentialFlow\n{\n    nNonOrthogonalCorrectors 3;\n}\n\n"
        "relaxationFactors\n{\n    fields\n    {\n        p               0.3;\n    }\n"
        "    equations\n    {\n        U               0.7;\n        k               0.5;\n"
        "        omega           0.5;\n    }\n}\n\n");
}

std::string transport_properties(const FoamCaseParams& p) {
    return dictionary(
        "constant", "transportProperties", p,
        "transportModel  Newtonian;\n\n// |Uinf| L / Re\nnu              " + number(foam_viscosity(p)) + ";\n\n");
}

std::string turbulence_properties(const FoamCaseParams& p) {
    return dictionary("constant", "turbulenceProperties", p,
                      "simulationType  RAS;\n\nRAS\n{\n    RASModel        kOmegaSST;\n\n    turbulence      on;\n\n"
                      "    printCoeffs     on;\n}\n\n");
}

void check_params(const FoamCaseParams& p) {
    const std::string where = "cannot write an OpenFOAM case: ";
    if (!(p.reynolds > 0.0) || !std::isfinite(p.reynolds))
        throw InputError(where + "FoamCaseParams::reynolds = " + format_number(p.reynolds) +
                         "; give a Reynolds number above 0");
    if (!(p.reference_length > 0.0) || !std::isfinite(p.reference_length))
        throw InputError(where + "FoamCaseParams::reference_length = " + format_number(p.reference_length) +
                         "; give a length above 0");
    if (!(p.velocity.norm() > 0.0) || !p.velocity.allFinite())
        throw InputError(where + "FoamCaseParams::velocity = " + vector_text(p.velocity) + "; give a velocity");
    if (!(p.turbulence_intensity > 0.0) || !(p.viscosity_ratio > 0.0) || p.iterations < 1)
        throw InputError(where +
                         "FoamCaseParams::turbulence_intensity, viscosity_ratio and iterations must be "
                         "above 0");
}

std::string without_trailing_slashes(std::string path) {
    while (path.size() > 1 && path.back() == '/') path.pop_back();
    return path;
}

}  // namespace

double foam_viscosity(const FoamCaseParams& p) {
    return p.velocity.norm() * p.reference_length / p.reynolds;
}

std::string foam_case_directory(const std::string& output) {
    const fs::path p(without_trailing_slashes(output));
    if (p.filename() == "polyMesh" && p.parent_path().filename() == "constant") {
        const fs::path dir = p.parent_path().parent_path();
        return dir.empty() ? "." : dir.string();
    }
    return p.string();
}

std::string foam_polymesh_path(const std::string& case_dir) {
    return (fs::path(without_trailing_slashes(case_dir)) / "constant" / "polyMesh").string();
}

std::vector<FoamCaseFile> foam_case_files(const std::vector<PolyPatch>& patches, const FoamCaseParams& params) {
    check_params(params);
    std::vector<FoamCaseFile> files = {{kDictionaries[0], control_dict(params)},
                                       {kDictionaries[1], fv_schemes(params)},
                                       {kDictionaries[2], fv_solution(params)},
                                       {kDictionaries[3], transport_properties(params)},
                                       {kDictionaries[4], turbulence_properties(params)}};
    for (std::size_t i = 0; i < kFields.size(); ++i)
        files.push_back({std::string("0.orig/") + kFields[i], field_file(i, patches, params)});
    return files;
}

std::vector<std::string> check_foam_case_output(const std::string& case_dir) {
    const std::string dir = without_trailing_slashes(case_dir);
    const fs::path parent = fs::path(dir).parent_path().empty() ? fs::path(".") : fs::path(dir).parent_path();
    const std::string where = "cannot write the OpenFOAM case '" + dir + "': ";
    std::error_code ec;
    if (!fs::is_directory(parent, ec))
        throw InputError(where + "directory '" + parent.string() +
                         "' does not exist; create it or choose another case directory");
    for (const char* sub : {"", "/constant", "/system", "/0.orig", "/0", "/constant/polyMesh"})
        if (fs::exists(dir + sub, ec) && !fs::is_directory(dir + sub, ec))
            throw InputError(where + "'" + dir + sub +
                             "' is a file, not a directory; remove it or choose another case directory");
    std::vector<std::string> outputs = {foam_polymesh_path(dir), dir + "/0"};
    std::vector<std::string> files(kDictionaries.begin(), kDictionaries.end());
    for (const char* f : kFields) files.push_back(std::string("0.orig/") + f);
    for (const std::string& f : files) {
        const std::string path = dir + "/" + f;
        if (fs::is_directory(path, ec))
            throw InputError(where + "'" + path +
                             "' is a directory, not a file; remove it or choose another case "
                             "directory");
        if (!fs::exists(path, ec)) outputs.push_back(path);
    }
    // Can the directories be made and the files written: the first that does not exist is
    // made where all the others go (the case, or a directory of it).
    if (!fs::exists(dir, ec)) {
        check_output_directory(dir);
        return outputs;
    }
    check_output_directory(dir + "/0");
    if (fs::is_directory(dir + "/constant", ec)) check_output_directory(foam_polymesh_path(dir));
    for (std::size_t i = 2; i < outputs.size(); ++i)
        if (fs::is_directory(fs::path(outputs[i]).parent_path(), ec)) check_output_path(outputs[i]);
    return outputs;
}

namespace {

/// Whether \p text names \p word as a whole (not inside a longer OpenFOAM word).
bool names_word(const std::string& text, const std::string& word) {
    auto part = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.'; };
    for (std::size_t at = text.find(word); at != std::string::npos; at = text.find(word, at + 1)) {
        const std::size_t end = at + word.size();
        if ((at == 0 || !part(text[at - 1])) && (end == text.size() || !part(text[end]))) return true;
    }
    return false;
}

/// The warnings of a kept field: a patch of the mesh it names nowhere.
void check_kept_field(const std::string& path, const std::string& text, const std::vector<PolyPatch>& patches,
                      std::vector<std::string>& warnings) {
    for (const PolyPatch& q : patches)
        if (!names_word(text, q.name))
            warnings.push_back("'" + path + "' (kept: the case's own) has no entry for the patch '" + q.name +
                               "'; add one, or delete the file to have Strata's");
}

/// The time directories of an earlier run in \p dir ("100", "0.5"; not "0"), sorted.
std::vector<std::string> earlier_results(const std::string& dir) {
    std::vector<std::string> times;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir, ec)) {
        const std::string name = e.path().filename().string();
        char* end = nullptr;
        const double t = std::strtod(name.c_str(), &end);
        if (e.is_directory(ec) && !name.empty() && end && *end == '\0' && t != 0.0) times.push_back(name);
    }
    std::sort(times.begin(), times.end(), [](const std::string& a, const std::string& b) {
        return std::strtod(a.c_str(), nullptr) < std::strtod(b.c_str(), nullptr);
    });
    return times;
}

/// The files of the case's 0.orig/ \p dir besides Strata's fields (nuTilda, a scalar of its
/// own), sorted; none where it does not exist. Hidden files (a writer's temporaries) are not fields.
std::vector<std::string> other_fields(const std::string& dir) {
    std::vector<std::string> names;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir, ec)) {
        const std::string name = e.path().filename().string();
        if (e.is_regular_file(ec) && name[0] != '.' && std::find(kFields.begin(), kFields.end(), name) == kFields.end())
            names.push_back(name);
    }
    std::sort(names.begin(), names.end());
    return names;
}

}  // namespace

FoamCaseWritten write_foam_case(const VolumeMesh& mesh, const std::string& case_dir, const FoamCaseParams& params,
                                Progress* progress, OutputSet* outputs) {
    FoamCaseWritten w;
    w.case_dir = without_trailing_slashes(case_dir);
    check_params(params);  // before anything is made
    check_foam_case_output(w.case_dir);
    const std::string dir = w.case_dir + "/";
    const std::vector<std::string> own_fields = other_fields(dir + "0.orig");
    OutputSet own;
    OutputSet& set = outputs ? *outputs : own;
    for (const char* sub : {"", "constant", "system", "0.orig"}) set.make_directory(dir + sub);
    const std::vector<PolyPatch> patches = write_polymesh(mesh, foam_polymesh_path(w.case_dir), progress, &set);
    AtomicDirectory& zero = set.directory(dir + "0");
    for (const FoamCaseFile& f : foam_case_files(patches, params)) {
        const std::string target = dir + f.path;
        const bool field = f.path.rfind("0.orig/", 0) == 0;
        std::string text = f.text;
        std::error_code ec;
        if (fs::exists(target, ec)) {
            const std::string there = read_whole_file(target);
            if (there == text) {
                w.unchanged.push_back(f.path);
            } else {
                w.kept.push_back(f.path);
                if (field) check_kept_field(target, there, patches, w.warnings);
                text = there;
            }
        } else {
            AtomicFile& out = set.file(target);
            write_whole_file(out.temp_path(), target, text);
            w.written.push_back(f.path);
        }
        if (field) write_whole_file(zero.file(f.path.substr(7)), dir + "0/" + f.path.substr(7), text);
    }
    // 0/ is a copy of 0.orig/: the case's own fields there too (nuTilda, a scalar of its own).
    for (const std::string& name : own_fields)
        write_whole_file(zero.file(name), dir + "0/" + name, read_whole_file(dir + "0.orig/" + name));
    const std::vector<std::string> times = earlier_results(w.case_dir);
    if (!times.empty()) {
        std::string list;
        for (const std::string& t : times) list += (list.empty() ? "" : ", ") + t;
        w.warnings.push_back("'" + w.case_dir + "' holds the results of an earlier run (times " + list +
                             "), which belong to the earlier mesh; remove them before running (foamListTimes -case " +
                             w.case_dir + " -rm)");
    }
    if (!outputs) own.commit();
    return w;
}

}  // namespace strata
