#pragma once
/// \file
/// The options every front-end (the strata program, the Python package) maps onto the Params
/// structs: the surface (PrepareParams with the switches a user spells differently), the layers
/// (LayerParams with its enums as text) and the rest of the hybrid mesh (HybridParams).
/// Defaults are the Params structs' own. Messages name the CLI's flags (--size, --remesh);
/// a front-end with other names translates them (translate_names).

#include <strata/geometry/prepare.h>
#include <strata/hybrid/hybrid_mesh.h>

#include <string>
#include <utility>
#include <vector>

namespace strata {

/// How the surface is made from the inputs: PrepareParams plus the switches that set several
/// of its fields at once.
struct SurfaceOptions {
    std::vector<std::string> inputs;   ///< CAD or surface-mesh files, read as one surface
    std::string input;                 ///< the inputs as one name, for messages (input_name)
    bool quads = false;                ///< recombine into quadrilaterals (CAD, or with remesh)
    double remesh = -1.0;              ///< remesh with this size (0: automatic); negative: no remeshing
    std::vector<int> mixed;            ///< CAD surface tags meshed with quads, triangles elsewhere
    std::vector<std::string> patches;  ///< "NAME=KIND" each
    PrepareParams prepare;
};

/// The inputs as one name for messages: "a.stl + b.stl".
std::string input_name(const std::vector<std::string>& inputs);

/// Some input is a CAD file (the rest may be surface meshes).
bool any_cad_input(const std::vector<std::string>& inputs);

/// Parse "NAME=KIND" items (InputError naming the item otherwise).
std::vector<std::pair<std::string, PatchKind>> parse_patch_options(const std::vector<std::string>& items);

/// The surface parameters from the options; surface-meshing options on a surface mesh, two
/// sizes at once and --mixed with --remesh are refused (InputError).
PrepareParams prepare_params(const SurfaceOptions& options);

/// Layer options: the LayerParams fields, plus the enums as text and the switches a user turns off.
struct LayerOptions {
    LayerParams params;
    std::string distribution{to_string(Distribution::Auto)};
    std::string normals{to_string(LayerParams{}.normals)};
    std::string proximity{to_string(LayerParams{}.proximity)};
    bool no_control = false, no_concave = false, no_hold_back = false;
};

/// The LayerParams of \p options (InputError for an unknown enum name).
LayerParams layer_params(const LayerOptions& options);

/// Hybrid options: the HybridParams fields beyond the layers.
struct MeshOptions {
    HybridParams params;
    std::string farfield{to_string(FarfieldParams{}.shape)};
};

/// The HybridParams of \p layers and \p mesh: the layers' threads are every stage's.
HybridParams hybrid_params(const LayerOptions& layers, const MeshOptions& mesh);

/// Library messages name parameters ("LayerParams::sweeps"); the CLI's flag of each (--sweeps).
const std::vector<std::pair<std::string, std::string>>& flag_of_parameter();

/// \p message with every name of \p names' first members replaced by the second ("LayerParams::
/// sweeps" -> "--sweeps"); a name followed by more identifier characters or a '-'
/// (CadParams::size_min, --size-min) is not taken for a shorter one (CadParams::size, --size).
std::string translate_names(std::string message, const std::vector<std::pair<std::string, std::string>>& names);

}  // namespace strata
