// solshape: Sol's shapes seen from outside, written as meshes for figures,
// Blender, MeshLab or a 3D printer (docs/shapes.md).
//
//   solshape sphere --radius R [--center X,Y,Z] [--resolution N] [--size-mm S] -o FILE.ply|.obj|.stl
//
// The meshes go through Assimp (Debian: libassimp-dev), which writes PLY,
// OBJ and (binary) STL from one in-memory scene; the file appears only when
// complete (sol::programs::OutputFile).
#include <assimp/Exporter.hpp>
#include <assimp/scene.h>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>

#include <sol/error.hpp>
#include <sol/shapes.hpp>

#include "command_line.hpp"
#include "output_file.hpp"

namespace {

// Assimp's exporter for a file name's extension: binary STL for printing,
// OBJ without a material file, ASCII PLY.
std::string format_of(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".ply") return "ply";
  if (ext == ".obj") return "objnomtl";
  if (ext == ".stl") return "stlb";
  return "";
}

// Writes `mesh` (scaled by `scale`) to `path` in `format` through Assimp.
void write_mesh(const sol::Mesh& mesh, double scale, const std::string& format, const std::string& path) {
  aiScene scene;  // its destructor frees what is attached below
  scene.mRootNode = new aiNode();
  scene.mMaterials = new aiMaterial*[1]{new aiMaterial()};
  scene.mNumMaterials = 1;
  scene.mMeshes = new aiMesh*[1]{new aiMesh()};
  scene.mNumMeshes = 1;
  scene.mRootNode->mMeshes = new unsigned int[1]{0};
  scene.mRootNode->mNumMeshes = 1;
  aiMesh& m = *scene.mMeshes[0];
  m.mMaterialIndex = 0;
  m.mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
  m.mNumVertices = static_cast<unsigned int>(mesh.vertices.size());
  m.mVertices = new aiVector3D[mesh.vertices.size()];
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const glm::dvec3 v = scale * mesh.vertices[i];
    m.mVertices[i] = aiVector3D(static_cast<ai_real>(v.x), static_cast<ai_real>(v.y), static_cast<ai_real>(v.z));
  }
  m.mNumFaces = static_cast<unsigned int>(mesh.triangles.size());
  m.mFaces = new aiFace[mesh.triangles.size()];
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    aiFace& f = m.mFaces[i];
    f.mNumIndices = 3;
    f.mIndices = new unsigned int[3];
    for (int k = 0; k < 3; ++k) f.mIndices[k] = static_cast<unsigned int>(mesh.triangles[i][static_cast<std::size_t>(k)]);
  }
  Assimp::Exporter exporter;
  if (exporter.Export(&scene, format, path) != AI_SUCCESS) {
    throw std::runtime_error(std::string("cannot write the mesh: ") + exporter.GetErrorString());
  }
}

int sphere(int argc, char** argv) {
  sol::cli::CommandLine cl("solshape sphere", "--radius R [options] -o FILE.ply|.obj|.stl",
                           "Writes a mesh of the geodesic sphere {p : d(center, p) = R} in Sol coordinates.");
  double radius = 0.0;
  std::optional<glm::dvec3> center;
  int resolution = 32;
  std::optional<double> size_mm;
  std::string output;
  cl.add_number("--radius", radius, "R",
                "the sphere's radius (Sol units), in (0, sqrt(2) pi = 4.4429): beyond, the sphere meets the cut "
                "locus of its centre and has creases, not built yet",
                sol::cli::CommandLine::Condition{[](double r) { return r > 0.0 && r < sol::kSmoothSphereRadius; },
                                                 "in (0, sqrt(2) pi = 4.4429)"});
  cl.add_vec3("--center", center, "X,Y,Z", "the centre (default 0,0,0)");
  cl.add_integer("--resolution", resolution, 1, 512, "N",
                 "each octant of directions in N^2 triangles: 8 N^2 triangles, 4 N^2 + 2 vertices (default 32)");
  cl.add_number("--size-mm", size_mm, "S",
                "scale the mesh so that its largest extent is S millimetres (STL's unit, for printing); without "
                "it, coordinates are Sol units",
                sol::cli::positive());
  cl.add_text("-o,--output", output, "FILE", "the mesh file: .ply (ASCII), .obj or .stl (binary)");
  cl.set_footer("Meshes are written with Assimp. docs/shapes.md has the construction and its accuracy.");
  cl.parse(argc, argv);
  if (radius == 0.0) cl.fail("--radius R is required");
  if (output.empty()) cl.fail("no output file: give -o FILE.ply|.obj|.stl");
  const std::string format = format_of(output);
  if (format.empty()) cl.fail(output + ": unknown mesh format (the name must end in .ply, .obj or .stl)");
  if (std::filesystem::is_directory(output)) cl.fail(output + ": cannot write: it is a directory");
  const sol::Mesh mesh = sol::geodesic_sphere(center.value_or(glm::dvec3(0.0)), radius, resolution);
  double scale = 1.0;
  if (size_mm) {
    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    for (const glm::dvec3& v : mesh.vertices) {
      lo = glm::min(lo, v);
      hi = glm::max(hi, v);
    }
    const glm::dvec3 extent = hi - lo;
    scale = *size_mm / std::max({extent.x, extent.y, extent.z});
  }
  sol::programs::OutputFile file(output);
  write_mesh(mesh, scale, format, file.path());
  file.commit();
  std::fprintf(stderr, "solshape: sphere of radius %g: %zu vertices, %zu triangles -> %s\n", radius, mesh.vertices.size(),
               mesh.triangles.size(), output.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  sol::programs::install_signal_cleanup();
  const std::string usage =
      "usage: solshape sphere --radius R [--center X,Y,Z] [--resolution N] [--size-mm S] -o FILE.ply|.obj|.stl\n"
      "Writes Sol's shapes as meshes (solshape sphere --help for the options).\n";
  if (argc < 2 || std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h") {
    std::fputs(usage.c_str(), argc < 2 ? stderr : stdout);
    return argc < 2 ? 2 : 0;
  }
  const std::string shape = argv[1];
  try {
    if (shape == "sphere") return sphere(argc - 1, argv + 1);
    std::fprintf(stderr, "solshape: unknown shape '%s' (known: sphere)\n", shape.c_str());
    return 2;
  } catch (const sol::InvalidArgument& e) {
    std::fprintf(stderr, "solshape: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "solshape: %s\n", e.what());
    return 1;
  }
}
