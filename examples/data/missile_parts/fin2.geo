// Fin 2 of the five-part STL case: a thin box 0.25 long, 0.01 thick, reaching from inside the
// body (radius 0.1) to 0.2 from its axis, turned 90 degrees about the x axis.
SetFactory("OpenCASCADE");
Box(1) = {1.2, -0.005, 0.05, 0.25, 0.01, 0.15};
Rotate {{1, 0, 0}, {0, 0, 0}, 1*Pi/2} { Volume{1}; }
Mesh.MeshSizeMax = 0.02;
