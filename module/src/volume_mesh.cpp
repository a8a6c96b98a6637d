#include <strata/module/volume_mesh.h>

namespace strata {

int cell_corners(CellType t) {
    switch (t) {
        case CellType::Tet: return 4;
        case CellType::Pyramid: return 5;
        case CellType::Prism: return 6;
        case CellType::Hex: return 8;
    }
    return 0;
}

std::string_view to_string(CellType t) {
    switch (t) {
        case CellType::Tet: return "tetrahedron";
        case CellType::Pyramid: return "pyramid";
        case CellType::Prism: return "prism";
        case CellType::Hex: return "hexahedron";
    }
    return "cell";
}

}  // namespace strata
