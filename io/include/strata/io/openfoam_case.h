#pragma once
/// \file
/// A ready-to-run OpenFOAM case round a polyMesh, for OpenFOAM v1912 (Debian 12's `openfoam`):
/// a steady incompressible RANS start with simpleFoam and k-omega SST (potentialFoam first, if
/// wished). Besides `constant/polyMesh` (openfoam.h) the case holds
///
///     system/controlDict, system/fvSchemes, system/fvSolution
///     constant/transportProperties (nu), constant/turbulenceProperties (RAS, kOmegaSST)
///     0.orig/U, p, k, omega, nut     the initial and boundary conditions, one entry per patch
///     0/                             a copy of 0.orig/: what the solvers read and overwrite
///
/// Every patch gets its conditions from its kind (foam_case_conditions). Lengths are the
/// mesh's (model units, which OpenFOAM takes for metres): the Reynolds number of
/// FoamCaseParams is kept whatever the unit. The texts depend on nothing but the patches and
/// the parameters (the same bytes run after run).

#include <strata/core/progress.h>
#include <strata/core/types.h>
#include <strata/core/volume_mesh.h>
#include <strata/io/files.h>
#include <strata/io/openfoam.h>

#include <string>
#include <vector>

namespace strata {

/// The flow the case starts: the freestream, the fluid's viscosity (from a Reynolds number) and
/// the freestream turbulence. Defaults: |U| = 1 along x, Re = 1e6 on a reference length of 1,
/// 1 % turbulence intensity, an eddy-viscosity ratio of 10.
struct FoamCaseParams {
    Vec3 velocity{1.0, 0.0, 0.0};        ///< U∞, model units per second
    double reynolds = 1e6;               ///< Re = |U∞| L / ν (> 0)
    double reference_length = 1.0;       ///< L, model units (> 0)
    double turbulence_intensity = 0.01;  ///< I: k∞ = 1.5 (I |U∞|)²
    double viscosity_ratio = 10.0;       ///< ν_t/ν in the freestream: ω∞ = k∞ / (ν ν_t/ν)
    int iterations = 500;                ///< controlDict's endTime (SIMPLE iterations)
    /// The mesh's first layer height and the y+ it gives (for the comments; 0: not said).
    double first_height = 0.0;
    double yplus = 0.0;
};

/// The kinematic viscosity ν = |U∞| L / Re of \p p.
double foam_viscosity(const FoamCaseParams& p);

/// The case directory that `-o` names with a case: \p output itself, or CASE for
/// "CASE/constant/polyMesh" (trailing slashes aside; "." for "constant/polyMesh").
std::string foam_case_directory(const std::string& output);

/// CASE/constant/polyMesh, where a case's mesh goes.
std::string foam_polymesh_path(const std::string& case_dir);

/// One file of a case: its path in the case ("system/controlDict", "0.orig/U") and its text.
struct FoamCaseFile {
    std::string path;
    std::string text;
};

/// The case's files besides the polyMesh and 0/, for \p patches (the boundary file's, as
/// write_polymesh returns them), in the order written: system/, constant/, 0.orig/. InputError
/// naming the parameter if \p params is out of range.
std::vector<FoamCaseFile> foam_case_files(const std::vector<PolyPatch>& patches, const FoamCaseParams& params);

/// Before the work: the case \p case_dir can be written. Its parent directory must exist
/// (InputError naming it, and what to do); the case and its `constant`, `system`, `0.orig` and
/// `0` must be directories where they exist, and the case's files to be written files
/// (InputError naming the one that is not); the directories can be created (OutputError, as
/// check_output_directory). Returns every output path: the polyMesh and 0/ (directories
/// replaced whole) and the case files that do not exist yet.
std::vector<std::string> check_foam_case_output(const std::string& case_dir);

/// What write_foam_case did.
struct FoamCaseWritten {
    std::string case_dir;
    std::vector<std::string> written;    ///< case files written, paths in the case ("system/controlDict")
    std::vector<std::string> unchanged;  ///< case files there already with the bytes Strata would write
    /// Case files there already with other bytes (the user's edits, or Strata's for another
    /// flow), left as they were.
    std::vector<std::string> kept;
    std::vector<std::string> warnings;  ///< what the user should know: a kept field without a patch, old results
};

/// Write \p mesh as the case \p case_dir (foam_case_directory of `-o`): created if it does not
/// exist (its parent must), with `constant/`, `system/` and `0.orig/`; the polyMesh replaced
/// whole (write_polymesh); each file of foam_case_files written only where the case has none
/// (one with other bytes, the user's edits, is kept and said in FoamCaseWritten::kept); `0/`
/// replaced whole by a copy of `0.orig/` (the files there, the user's or Strata's), since what a
/// solver left in `0/` (potentialFoam's field) belongs to the previous mesh. Staged in \p outputs
/// (committed with the run's other outputs) or, without it, committed here: all or nothing, the
/// directories made for it removed again on failure. Throws what write_polymesh and the checks
/// throw.
FoamCaseWritten write_foam_case(const VolumeMesh& mesh, const std::string& case_dir, const FoamCaseParams& params,
                                Progress* progress = nullptr, OutputSet* outputs = nullptr);

}  // namespace strata
