#include <strata/core/enum_names.h>
#include <strata/core/surface_mesh.h>

#include <algorithm>
#include <cctype>
#include <string>

namespace strata {

constexpr EnumNames<PatchKind, 4> kPatchKindNames{{"wall", "symmetry", "farfield", "other"}};

std::string_view to_string(PatchKind kind) {
    return kPatchKindNames.name(kind);
}

PatchKind parse_patch_kind(std::string_view text) {
    return kPatchKindNames.parse(text, "patch kind");
}

void SurfaceMesh::add_face(const Index* nodes, Index n, Index patch) {
    face_nodes.insert(face_nodes.end(), nodes, nodes + n);
    face_offsets.push_back(static_cast<Index>(face_nodes.size()));
    face_patch.push_back(patch);
}

void SurfaceMesh::add_face(std::initializer_list<Index> nodes, Index patch) {
    add_face(nodes.begin(), static_cast<Index>(nodes.size()), patch);
}

Index SurfaceMesh::num_triangles() const {
    Index n = 0;
    for (Index f = 0; f < num_faces(); ++f) n += face_size(f) == 3;
    return n;
}

Index SurfaceMesh::num_quads() const {
    Index n = 0;
    for (Index f = 0; f < num_faces(); ++f) n += face_size(f) == 4;
    return n;
}

void flip_faces(SurfaceMesh& mesh) {
    for (Index f = 0; f < mesh.num_faces(); ++f)
        std::reverse(mesh.face_nodes.begin() + mesh.face_offsets[f] + 1,
                     mesh.face_nodes.begin() + mesh.face_offsets[f + 1]);
}

Index find_patch(const SurfaceMesh& mesh, std::string_view name) {
    for (std::size_t i = 0; i < mesh.patches.size(); ++i)
        if (mesh.patches[i].name == name) return static_cast<Index>(i);
    return kNone;
}

std::string patch_word(std::string_view name, std::size_t index) {
    std::string w;
    bool replaced = false;  // the last character written stands for characters replaced
    for (const char c : name) {
        const auto u = static_cast<unsigned char>(c);
        if (std::isalnum(u) || c == '_' || c == '-' || c == '.') {
            w += c;
            replaced = false;
        } else if (!replaced) {
            w += '_';
            replaced = true;
        }
    }
    if (replaced) w.pop_back();
    if (w.empty()) return "patch_" + std::to_string(index + 1);
    if (!std::isalpha(static_cast<unsigned char>(w[0])) && w[0] != '_') return "patch_" + w;
    return w;
}

}  // namespace strata
