#pragma once
/// \file
/// The options every front-end (the strata program, the Python package) maps onto the Params
/// structs: the surface (PrepareParams with the switches a user spells differently), the layers
/// (LayerParams with its enums as text) and the rest of the hybrid mesh (HybridParams).
/// Defaults are the Params structs' own. Each option is listed once (option_table: its flag,
/// keyword, parameter, help and field): the CLI and Python both register from that list.
/// Messages name the CLI's flags (--size, --remesh); a front-end with other names translates
/// them (translate_names).

#include <strata/hybrid/hybrid_mesh.h>
#include <strata/surface/prepare.h>

#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace strata {

/// How the surface is made from the inputs: PrepareParams plus the switches that set several
/// of its fields at once.
struct SurfaceOptions {
    std::vector<std::string> inputs;   ///< CAD or surface-mesh files, read as one surface
    std::string input;                 ///< the inputs as one name, for messages (input_name)
    bool quads = false;                ///< recombine into quadrilaterals (CAD, or with remesh)
    double remesh = -1.0;              ///< remesh with this size (0: automatic); negative: no remeshing
    double wrap = -1.0;                ///< alpha-wrap with this α (0: automatic), then remesh; negative: no wrap
    std::vector<int> mixed;            ///< CAD surface tags meshed with quads, triangles elsewhere
    std::vector<std::string> patches;  ///< "NAME=KIND" each
    PrepareParams prepare;
};

/// The inputs as one name for messages: "a.stl + b.stl".
std::string input_name(const std::vector<std::string>& inputs);

/// Some input is a CAD file (the rest may be surface meshes).
bool any_cad_input(const std::vector<std::string>& inputs);

/// Parse "NAME=KIND" and "NAME=KIND:NEWNAME" items into kinds (InputError naming the item otherwise).
std::vector<std::pair<std::string, PatchKind>> parse_patch_options(const std::vector<std::string>& items);

/// The renames of "NAME=KIND:NEWNAME" items (NAME, NEWNAME), in order; items without one add none.
std::vector<std::pair<std::string, std::string>> parse_patch_renames(const std::vector<std::string>& items);

/// The surface parameters from the options; surface-meshing options on a surface mesh, two
/// sizes at once and --mixed with --remesh are refused (InputError). With \p layers (the
/// layers and mesh commands), CAD walls are sized for the first layer's height
/// (CadParams::first_height, in the CAD's unit: the height over PrepareParams::scale).
/// With no first height asked (automatic_first_height), the walls are not sized until it is
/// chosen from them (run(), size_walls_for_layers).
PrepareParams prepare_params(const SurfaceOptions& options, const LayerParams* layers = nullptr);

/// \p p's walls sized for a first layer \p first_height high (CadParams::first_height in the
/// CAD's unit, RemeshParams::first_height) and \p layers' fans, where a wall aspect ratio is
/// asked (CadParams::max_aspect_ratio).
void size_walls_for_layers(PrepareParams& p, const LayerParams& layers, double first_height);

/// What to add to an error about an open surface when sewing a CAD model's faces left cracks
/// (SewReport::cracks): "; ... --sew-tolerance T sews them", or empty.
std::string sewing_hint(const SewReport& sew);

/// Layer options: the LayerParams fields, plus the enums as text.
struct LayerOptions {
    LayerParams params;
    std::string distribution{to_string(Distribution::Auto)};
    std::string normals{to_string(LayerParams{}.normals)};
    std::string proximity{to_string(LayerParams{}.proximity)};
};

/// The LayerParams of \p options (InputError for an unknown enum name, a negative thread count,
/// or a distribution that resolve() refuses; with no first height, as it would with one chosen).
LayerParams layer_params(const LayerOptions& options);

/// Hybrid options: the HybridParams fields beyond the layers.
struct MeshOptions {
    HybridParams params;
    std::string farfield{to_string(FarfieldParams{}.shape)};
    std::string tets{to_string(TetFillParams{}.mesher)};
};

/// The HybridParams of \p layers and \p mesh: the layers' threads are every stage's.
HybridParams hybrid_params(const LayerOptions& layers, const MeshOptions& mesh);

/// How a volume mesh is written besides its format (the layers and mesh commands).
struct OutputOptions {
    /// The output names an OpenFOAM case directory (CASE, or CASE/constant/polyMesh): the
    /// polyMesh and a ready-to-run simpleFoam case round it (io/openfoam_case.h, pipeline.h's
    /// foam_case_params).
    bool foam_case = false;
};

/// Everything a front-end sets: how the surface is made, the layers, the rest of the mesh, how
/// it is written.
struct Options {
    SurfaceOptions surface;
    LayerOptions layers;
    MeshOptions mesh;
    OutputOptions output;
};

/// The options that give \p mesh and \p prepare (their names for the enums: layer_params and
/// hybrid_params of them give the same values): a library caller's parameters as a front-end's,
/// for the report's provenance.
Options options_of(const HybridParams& mesh, const PrepareParams& prepare);

/// Where an option applies: how the surface is made (every CLI command; Python's surface(),
/// layers() and mesh()), the patches and orientation (those, and a Gmsh model meshed in
/// place: Python's gmsh.mesh_current_model()), the layers (layers and mesh, and a Gmsh
/// model), the rest of the hybrid mesh (mesh, and a Gmsh model), how a volume mesh is written
/// (layers and mesh; not a Gmsh model, which stays in Gmsh).
enum class OptionStage { Surface, Patches, Layers, Mesh, Output };

/// One option of the front-ends: the CLI's flag, the Python keyword, the library parameter it
/// sets, its help and the field it binds. The one list of them (option_table): the CLI
/// registers its flags from it, Python its keywords, and the messages' names are translated
/// by it.
struct OptionSpec {
    using Field =
        std::variant<double& (*)(Options&), int& (*)(Options&), bool& (*)(Options&), std::string& (*)(Options&),
                     std::vector<int>& (*)(Options&), std::vector<std::string>& (*)(Options&)>;
    std::string flag;     ///< "--size"; empty: not on the command line
    std::string keyword;  ///< "size"; empty: not a Python keyword
    std::string param;    ///< the parameter library messages name ("CadParams::size"); empty: a front-end switch
    OptionStage stage = OptionStage::Surface;
    std::string help;          ///< the CLI's help (Python's doc: the same, its flags named as keywords)
    std::string keyword_help;  ///< Python's doc where it says something else (a switch the flag turns off)
    Field field;
    bool flag_sets_false = false;  ///< a switch the flag turns off (--no-control: control_functions false)
    bool show_default = true;      ///< the CLI's help shows the default
    /// A size or nothing (a double field, negative for off): on the command line the flag alone
    /// (0: an automatic size) or followed by a number; in Python None or a number >= 0.
    bool optional_size = false;
};

/// Every option, in the order of the CLI's help.
const std::vector<OptionSpec>& option_table();

/// Library messages name parameters ("LayerParams::sweeps"); the CLI's flag of each (--sweeps).
const std::vector<std::pair<std::string, std::string>>& flag_of_parameter();

/// The same to Python keywords: parameters and flags ("LayerParams::sweeps", "--sweeps" ->
/// "sweeps").
const std::vector<std::pair<std::string, std::string>>& keyword_of_name();

/// \p message with every name of \p names' first members replaced by the second ("LayerParams::
/// sweeps" -> "--sweeps"); a name followed by more identifier characters or a '-'
/// (CadParams::size_min, --size-min) is not taken for a shorter one (CadParams::size, --size).
std::string translate_names(std::string message, const std::vector<std::pair<std::string, std::string>>& names);

}  // namespace strata
