// Broken and hostile FBX files (importers/fbx_document.h, fbx_scene.h): each
// is refused with one line naming the file and the problem, or loads what is
// sound with a warning naming what was left out. Result tests are in
// fbx_scene_test.cpp.
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "importers/load_face.h"
#include "tests/common/fbx_test_files.h"
#include "tests/common/test_support.h"

// Named, so that its helpers do not meet other files' in a unity build.
namespace fbx_validity_test {
namespace {

using testing_support::FbxTestNode;
using testing_support::fbxBinary;
using testing_support::fbxDoubles;
using testing_support::fbxInt;
using testing_support::fbxInts;
using testing_support::fbxLong;
using testing_support::fbxName;
using testing_support::fbxString;

std::vector<uint8_t> bytesOf(const std::string& s) { return {s.begin(), s.end()}; }

// A triangle: one Geometry on one mesh Model, `vertices` and `polygons` as given.
std::string triangle(const std::vector<double>& vertices = {0, 0, 0, 1, 0, 0, 0, 1, 0},
                     const std::vector<int32_t>& polygons = {0, 1, ~2}, std::vector<FbxTestNode> extraObjects = {},
                     std::vector<FbxTestNode> extraConnections = {}, uint32_t version = 7400) {
  FbxTestNode objects{"Objects",
                      {},
                      {{"Geometry",
                        {fbxLong(10), fbxString(fbxName("Tri", "Geometry")), fbxString("Mesh")},
                        {{"Vertices", {fbxDoubles(vertices)}, {}}, {"PolygonVertexIndex", {fbxInts(polygons)}, {}}}},
                       {"Model", {fbxLong(20), fbxString(fbxName("Tri", "Model")), fbxString("Mesh")}, {}}}};
  for (FbxTestNode& o : extraObjects) objects.children.push_back(std::move(o));
  FbxTestNode connections{"Connections",
                          {},
                          {{"C", {fbxString("OO"), fbxLong(10), fbxLong(20)}, {}}, {"C", {fbxString("OO"), fbxLong(20), fbxLong(0)}, {}}}};
  for (FbxTestNode& c : extraConnections) connections.children.push_back(std::move(c));
  return fbxBinary({objects, connections}, version);
}

// What loading `bytes` as the file `name` says: the error, or "loaded" and its warnings.
std::string outcomeOf(const std::string& bytes, const std::string& name = "broken.fbx") {
  auto face = importers::loadFaceFromBytes(bytesOf(bytes), name);
  if (!face) return face.error().message;
  std::string out = "loaded";
  for (const std::string& w : face->model.warnings) out += "; " + w;
  return out;
}

TEST(FbxValidity, ASoundTriangleLoads) {
  EXPECT_EQ(outcomeOf(triangle()), "loaded");
  auto face = importers::loadFaceFromBytes(bytesOf(triangle()), "tri.fbx");
  ASSERT_TRUE(face);
  EXPECT_EQ(face->format, importers::FaceFormat::Fbx);
  ASSERT_EQ(face->model.meshes.size(), 1u);
  EXPECT_EQ(face->model.meshes[0].primitives[0].indices.size(), 3u);
}

TEST(FbxValidity, SixtyFourBitRecordsOfFbx2016AndLaterLoad) {
  for (uint32_t version : {7500u, 7700u}) {
    auto face = importers::loadFaceFromBytes(bytesOf(triangle({0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 1, ~2}, {}, {}, version)), "tri.fbx");
    ASSERT_TRUE(face) << version << ": " << face.error().message;
    EXPECT_EQ(face->model.meshes.at(0).primitives.at(0).indices.size(), 3u) << version;
  }
  // The same bytes read with 32-bit headers are not an FBX 7.4 file.
  std::string misread = triangle({0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 1, ~2}, {}, {}, 7500);
  misread[23] = char(0xe8), misread[24] = char(0x1c);  // version 7400
  EXPECT_NE(outcomeOf(misread), "loaded");
}

TEST(FbxValidity, BrokenFilesAreOneLineNamingTheFile) {
  const std::string sound = triangle();
  std::string cutHeader = sound.substr(0, 24);
  std::string endPastFile = sound;
  endPastFile[27] = char(0xff), endPastFile[28] = char(0xff);  // the first node's end offset
  std::string manyValues = sound;
  manyValues[31] = char(0xff), manyValues[32] = char(0xff);  // the first node's value count
  std::string unknownType = fbxBinary({{"Objects", {std::string("Z") + "\x01\x02"}, {}}});
  std::string liedArray = fbxBinary({{"Objects", {std::string("d\x10\0\0\0\0\0\0\0\x08\0\0\0", 13) + std::string(8, '\0')}, {}}});
  std::string garbageZlib = fbxBinary({{"Objects", {std::string("d\x02\0\0\0\x01\0\0\0\x08\0\0\0", 13) + "notzlib!"}, {}}});
  // 2^31 doubles claimed from 8 bytes: refused by the load budget before anything is inflated.
  std::string bomb = fbxBinary({{"Objects", {std::string("d\0\0\0\x80\x01\0\0\0\x08\0\0\0", 13) + "notzlib!"}, {}}});
  FbxTestNode deep{"Leaf", {fbxInt(1)}, {}};
  for (int k = 0; k < 100; ++k) deep = FbxTestNode{"Nest", {fbxInt(k)}, {deep}};
  std::string tooDeep = fbxBinary({deep});
  std::string oldVersion = fbxBinary({}, 6100);
  std::string nanVertex = triangle({0, 0, 0, 1, 0, 0, 0, std::nan(""), 0});
  std::string pastVertices = triangle({0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 1, ~7});
  std::string noObjects = fbxBinary({{"Connections", {}, {}}});
  // Two Models, each the other's parent.
  std::string cycle =
      triangle({0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 1, ~2}, {{"Model", {fbxLong(30), fbxString(fbxName("Other", "Model")), fbxString("Null")}, {}}},
               {{"C", {fbxString("OO"), fbxLong(20), fbxLong(30)}, {}}, {"C", {fbxString("OO"), fbxLong(30), fbxLong(20)}, {}}});
  const std::string asciiHead = "; FBX 7.4.0 project file\n";
  struct Case {
    const char* what;
    std::string bytes;
    const char* says;
  };
  const Case cases[] = {
      {"header cut short", cutHeader, "cut short"},
      {"a node ending past the file", endPastFile, "ends at byte"},
      {"more values than bytes", manyValues, "values in"},
      {"an unknown value type", unknownType, "unknown type 'Z'"},
      {"a plain array whose size lies", liedArray, "elements of 8 bytes stored in 8"},
      {"an array that is not zlib", garbageZlib, "does not inflate"},
      {"a zlib bomb", bomb, "FBX array"},
      {"nodes 100 deep", tooDeep, "nested deeper than 64"},
      {"FBX 6", oldVersion, "FBX version 6100"},
      {"a NaN vertex", nanVertex, "not a finite number"},
      {"a polygon past the vertices", pastVertices, "names vertex 7 of 3"},
      {"no Objects", noObjects, "without an Objects section"},
      {"a parent cycle", cycle, "its own ancestor"},
      {"ASCII: an unclosed string", asciiHead + "Objects: {\n  Model: 1, \"Model::Face, Mesh {\n", "a string that is never closed"},
      {"ASCII: an unclosed node", asciiHead + "Objects: {\n  Model: 1, \"Model::Face\", \"Mesh\" {\n", "never closed ('}')"},
      {"ASCII: an array of the wrong size", asciiHead + "Objects: {\n Geometry: 1, \"Geometry::G\", \"Mesh\" {\n  Vertices: *4 {\n   a: 1,2,3\n  }\n }\n}\n",
       "says 4 elements and has 3"},
      {"ASCII: a stray character", asciiHead + "Objects: {\n : 5\n}\n", "line 3"},
      {"ASCII FBX 6", "; FBX 6.1.0 project file\nObjects: {\n}\n", "FBX 6 or older"},
  };
  for (const Case& c : cases) {
    const std::string said = outcomeOf(c.bytes);
    EXPECT_EQ(said.find('\n'), std::string::npos) << c.what << ": " << said;
    EXPECT_EQ(said.rfind("broken.fbx: ", 0), 0u) << c.what << ": " << said;
    EXPECT_NE(said.find(c.says), std::string::npos) << c.what << ": " << said;
  }
}

TEST(FbxValidity, AnUnusableMeshIsSkippedWithAWarningNamingIt) {
  // A second Geometry whose polygon names a vertex past its end: the sound triangle still loads.
  const std::string bytes =
      triangle({0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 1, ~2},
               {{"Geometry",
                 {fbxLong(40), fbxString(fbxName("Bad", "Geometry")), fbxString("Mesh")},
                 {{"Vertices", {fbxDoubles(std::vector<double>{0, 0, 0})}, {}}, {"PolygonVertexIndex", {fbxInts(std::vector<int32_t>{0, 1, ~2})}, {}}}},
                {"Model", {fbxLong(50), fbxString(fbxName("Bad", "Model")), fbxString("Mesh")}, {}}},
               {{"C", {fbxString("OO"), fbxLong(40), fbxLong(50)}, {}}, {"C", {fbxString("OO"), fbxLong(50), fbxLong(0)}, {}}});
  const std::string said = outcomeOf(bytes);
  EXPECT_EQ(said.rfind("loaded; ", 0), 0u) << said;
  EXPECT_NE(said.find("geometry 'Bad': polygon 0 names vertex 1 of 1; mesh skipped"), std::string::npos) << said;
}

TEST(FbxValidity, BlendShapesAndTexturesThatCannotBeUsedAreWarnings) {
  // A shape naming a vertex past the mesh, a shape whose offsets do not pair
  // with its indexes, and a texture named by a file that is not there.
  auto shape = [](int64_t id, const char* name, std::vector<int32_t> indexes, std::vector<double> offsets) {
    return FbxTestNode{"Geometry",
                       {fbxLong(id), fbxString(fbxName(name, "Geometry")), fbxString("Shape")},
                       {{"Indexes", {fbxInts(indexes)}, {}}, {"Vertices", {fbxDoubles(offsets)}, {}}}};
  };
  auto channel = [](int64_t id, const char* name) {
    return FbxTestNode{"Deformer", {fbxLong(id), fbxString(fbxName(name, "SubDeformer")), fbxString("BlendShapeChannel")}, {}};
  };
  auto link = [](int64_t child, int64_t parent, const char* property = nullptr) {
    FbxTestNode c{"C", {fbxString(property ? "OP" : "OO"), fbxLong(child), fbxLong(parent)}, {}};
    if (property) c.values.push_back(fbxString(property));
    return c;
  };
  const std::string bytes = triangle(
      {0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 1, ~2},
      {{"Deformer", {fbxLong(100), fbxString(fbxName("Shapes", "Deformer")), fbxString("BlendShape")}, {}},
       channel(101, "jawOpen"), shape(102, "jawOpen", {0, 9}, {0, -1, 0, 0, -1, 0}),
       channel(103, "mouthSmile_L"), shape(104, "mouthSmile_L", {0, 1}, {1, 0, 0}),
       channel(105, "browInnerUp"), shape(106, "browInnerUp", {2}, {0, 0.5, 0}),
       {"Material", {fbxLong(200), fbxString(fbxName("Skin", "Material")), fbxString("")}, {}},
       {"Texture", {fbxLong(201), fbxString(fbxName("SkinTex", "Texture")), fbxString("")}, {{"RelativeFilename", {fbxString("textures/skin.png")}, {}}}}},
      {link(100, 10), link(101, 100), link(102, 101), link(103, 100), link(104, 103), link(105, 100), link(106, 105), link(200, 20),
       link(201, 200, "DiffuseColor")});
  auto face = importers::loadFaceFromBytes(bytesOf(bytes), "warned.fbx");
  ASSERT_TRUE(face) << face.error().message;
  EXPECT_EQ(face->model.meshes[0].targetNames, std::vector<std::string>{"browInnerUp"}) << "the sound shape is kept";
  std::string warnings;
  for (const std::string& w : face->model.warnings) warnings += w + "\n";
  EXPECT_NE(warnings.find("blend shape 'jawOpen' names a vertex past 3"), std::string::npos) << warnings;
  EXPECT_NE(warnings.find("blend shape 'mouthSmile_L': 2 indexes and 3 offset coordinates do not pair"), std::string::npos) << warnings;
  EXPECT_NE(warnings.find("texture 'SkinTex': 'textures/skin.png' is not beside the FBX"), std::string::npos) << warnings;
}

TEST(FbxValidity, ObjectsThatReuseAnIdAreLeftOutWithAWarning) {
  // The fuzzer's first finding: a second Model with the first one's id was
  // made a node that no parent was ever set for (index -1 under UBSan).
  const std::string bytes =
      triangle({0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 1, ~2}, {{"Model", {fbxLong(20), fbxString(fbxName("Again", "Model")), fbxString("Null")}, {}}});
  const std::string said = outcomeOf(bytes);
  EXPECT_EQ(said, "loaded; 1 object(s) reuse an earlier object's id; the earlier one is read");
  const std::string found = testing_support::readTextFile(testing_support::sourceDir() / "tests" / "importers" / "fbx" / "fuzz_model_id_twice.fbx");
  EXPECT_FALSE(found.empty());
  EXPECT_EQ(outcomeOf(found).find('\n'), std::string::npos) << "the fuzzer's input, loaded or refused in one line";
}

TEST(FbxValidity, AnotherScaleInheritanceUnderANonUniformScaleIsAWarning) {
  // The triangle's Model under a Null scaled (1, 2, 1), inheriting RrSs (InheritType 0).
  auto build = [](int inheritType) {
    FbxTestNode parent{"Model", {fbxLong(30), fbxString(fbxName("Stretched", "Model")), fbxString("Null")},
                       {testing_support::fbxVectorProperties({{"Lcl Scaling", {1.0, 2.0, 1.0}}})}};
    FbxTestNode child{"Model", {fbxLong(20), fbxString(fbxName("Tri", "Model")), fbxString("Mesh")},
                      {{"Properties70", {}, {{"P", {fbxString("InheritType"), fbxString("enum"), fbxString(""), fbxString(""), fbxInt(inheritType)}, {}}}}}};
    FbxTestNode objects{"Objects",
                        {},
                        {{"Geometry",
                          {fbxLong(10), fbxString(fbxName("Tri", "Geometry")), fbxString("Mesh")},
                          {{"Vertices", {fbxDoubles(std::vector<double>{0, 0, 0, 1, 0, 0, 0, 1, 0})}, {}},
                           {"PolygonVertexIndex", {fbxInts(std::vector<int32_t>{0, 1, ~2})}, {}}}},
                         child, parent}};
    FbxTestNode connections{"Connections",
                            {},
                            {{"C", {fbxString("OO"), fbxLong(10), fbxLong(20)}, {}},
                             {"C", {fbxString("OO"), fbxLong(20), fbxLong(30)}, {}},
                             {"C", {fbxString("OO"), fbxLong(30), fbxLong(0)}, {}}}};
    return fbxBinary({objects, connections});
  };
  EXPECT_EQ(outcomeOf(build(1)), "loaded") << "RSrs: a node graph's own way";
  EXPECT_EQ(outcomeOf(build(0)),
            "loaded; 1 Model(s) under a non-uniform scale inherit it another way than RSrs (InheritType 0 or 2); read as RSrs, they may show sheared");
}

TEST(FbxValidity, AChainOfFiftyThousandModelsLoadsInLinearWork) {
  // Each Model the parent of the next, the triangle's at the end: a walk to
  // the root per node (cycle check, inherited scale) would be 1.25e9 steps.
  constexpr int kChain = 50000;
  std::vector<FbxTestNode> models;
  std::vector<FbxTestNode> links;
  for (int k = 0; k < kChain; ++k) {
    models.push_back({"Model", {fbxLong(1000 + k), fbxString(fbxName("Link", "Model")), fbxString("Null")}, {}});
    links.push_back({"C", {fbxString("OO"), fbxLong(1000 + k), fbxLong(k == 0 ? 0 : 999 + k)}, {}});
  }
  links.push_back({"C", {fbxString("OO"), fbxLong(20), fbxLong(1000 + kChain - 1)}, {}});
  auto face = importers::loadFaceFromBytes(bytesOf(triangle({0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 1, ~2}, models, links)), "chain.fbx");
  ASSERT_TRUE(face) << face.error().message;
  EXPECT_EQ(face->model.nodes.size(), size_t(kChain) + 2) << "the root, the chain and the triangle's Model";
}

TEST(FbxValidity, AsciiFbxReadsAsTheBinaryDoes) {
  const std::string ascii =
      "; FBX 7.4.0 project file\n"
      "; a comment\n"
      "GlobalSettings:  {\n\tVersion: 1000\n\tProperties70:  {\n"
      "\t\tP: \"UnitScaleFactor\", \"double\", \"Number\", \"\",100\n\t}\n}\n"
      "Objects:  {\n"
      "\tGeometry: 10, \"Geometry::Tri\", \"Mesh\" {\n"
      "\t\tVertices: *12 {\n\t\t\ta: 0,0,0,1,0,0,1,1,0,\n0,1,0\n\t\t} \n"
      "\t\tPolygonVertexIndex: *4 {\n\t\t\ta: 0,1,2,-4\n\t\t} \n"
      "\t\tLayerElementUV: 0 {\n\t\t\tMappingInformationType: \"ByVertice\"\n\t\t\tReferenceInformationType: \"Direct\"\n"
      "\t\t\tUV: *8 {\n\t\t\t\ta: 0,0,1,0,1,1,0,1\n\t\t\t}\n\t\t}\n"
      "\t}\n"
      "\tModel: 20, \"Model::Quad\", \"Mesh\" {\n\t\tProperties70:  {\n"
      "\t\t\tP: \"Lcl Translation\", \"Lcl Translation\", \"\", \"A\",0.5,0,0\n\t\t}\n\t\tShading: T\n\t}\n"
      "}\n"
      "Connections:  {\n\tC: \"OO\",10,20\n\tC: \"OO\",20,0\n}\n";
  auto face = importers::loadFaceFromBytes(bytesOf(ascii), "quad.fbx");
  ASSERT_TRUE(face) << face.error().message;
  const eng::Model& model = face->model;
  ASSERT_EQ(model.meshes.size(), 1u);
  const eng::Primitive& p = model.meshes[0].primitives[0];
  EXPECT_EQ(p.positions.size(), 4u);
  EXPECT_EQ(p.indices.size(), 6u) << "the quad fanned into two triangles";
  ASSERT_EQ(p.texcoords.size(), 4u);
  for (size_t v = 0; v < 4; ++v) {
    if (p.positions[v] == glm::vec3(1, 1, 0)) {
      EXPECT_EQ(p.texcoords[v], glm::vec2(1, 0)) << "V flipped to glTF's";
    }
  }
  const eng::Aabb box = model.bounds();
  EXPECT_NEAR(box.min.x, 0.5f, 1e-6f) << "Lcl Translation, in metres (UnitScaleFactor 100)";
  EXPECT_NEAR(box.max.x, 1.5f, 1e-6f);
}

}  // namespace
}  // namespace fbx_validity_test
