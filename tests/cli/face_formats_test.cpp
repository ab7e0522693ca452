// Every face format through the one loader (importers::loadFace) and the commands:
// VRM 0.x / 1.0 avatars, the CANDIDE-3 mask (with --shape identity
// parameters), OBJ keyframe folders; and --background for compositing
// (transparent RGBA with a clean edge, or one colour).
#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "app/face_setup.h"
#include "engine/scene/file_bytes.h"
#include "engine/scene/glb_container.h"
#include "importers/load_face.h"
#include "tests/cli/cli_runner.h"
#include "tests/cli/cli_test_support.h"
#include "tests/common/test_face.h"
#include "tests/common/study_obj_set.h"
#include "tests/common/test_support.h"

namespace cli_test {
namespace {

std::filesystem::path vrmPath(int version) {
  return testing_support::sharedDir() / "assets" / "vrm" /
         (version == 0 ? "modifier_shapekey_vrm0.vrm" : "modifier_shapekey_vrm1.vrm");
}
std::filesystem::path candidePath() { return testing_support::sharedDir() / "candide3" / "candide3.wfm"; }

bool contains(const std::string& text, const std::string& needle) { return text.find(needle) != std::string::npos; }

TEST(FaceFormats, RigReportsVrm0And1ExpressionsEmotionsAndVisemes) {
  FACIAL_REQUIRE_SHARED();
  const CommandOutput v0 = runFacial({"rig", vrmPath(0).string()});
  ASSERT_EQ(v0.exitCode, 0) << v0.err;
  EXPECT_TRUE(contains(v0.out, "(VRM): 1 morph weight(s)")) << v0.out;
  EXPECT_TRUE(contains(v0.out, "expression stage: VRM 0.x blend shape groups, 13 expressions over 1 morph targets"))
      << v0.out;
  EXPECT_TRUE(contains(v0.out, "emotion happy <- 'joy'")) << v0.out;
  EXPECT_TRUE(contains(v0.out, "emotion disgust <- 'angry' x0.5 + 'sorrow' x0.3 (composed)")) << v0.out;
  EXPECT_TRUE(contains(v0.out, "visemes (5, lip sync): a, i, u, e, o")) << v0.out;
  EXPECT_FALSE(contains(v0.err, "extension VRM ignored")) << v0.err;

  const CommandOutput v1 = runFacial({"rig", vrmPath(1).string(), "--json"});
  ASSERT_EQ(v1.exitCode, 0) << v1.err;
  const nlohmann::json report = nlohmann::json::parse(v1.out, nullptr, false);
  ASSERT_FALSE(report.is_discarded()) << v1.out;
  EXPECT_EQ(report["format"], "VRM");
  EXPECT_EQ(report["scheme"], "emotion expressions (VRM)");
  EXPECT_EQ(report["visemes"], nlohmann::json::array({"aa", "ih", "ou", "ee", "oh"}));
  EXPECT_EQ(report["emotions"][1], "happy <- 'happy'");
  EXPECT_TRUE(contains(report["emotions"][4].get<std::string>(), "fear <- ")) << report["emotions"];
  EXPECT_TRUE(contains(report["emotions"][4].get<std::string>(), "(composed)")) << report["emotions"];
}

TEST(FaceFormats, VrmOpensInExpressRenderInfoAndSheet) {
  FACIAL_REQUIRE_SHARED();
  const std::filesystem::path dir = testing_support::freshTempDir("face_formats_vrm");
  for (int version : {0, 1}) {
    const std::string model = vrmPath(version).string();
    const std::string tag = "v" + std::to_string(version);
    EXPECT_TRUE(ranCleanly(runFacial({"express", "happy", "--model", model, "--size", "96x96", "--out",
                                      (dir / (tag + "_happy.png")).string()})));
    const CommandOutput info = runFacial({"info", model});
    EXPECT_EQ(info.exitCode, 0) << info.err;
    // The extension the VRM importer reads is reported as read, not as unknown to the glTF loader.
    EXPECT_TRUE(contains(info.out, version == 0 ? "VRM " : "VRMC_vrm ")) << info.out;
    EXPECT_TRUE(contains(info.out, "applied: " + std::to_string(version == 0 ? 13 : 18) + " expressions")) << info.out;
    EXPECT_FALSE(contains(info.out, "not supported by this loader")) << info.out;
    // The shape key the files bind to the open vowel moves the mesh.
    EXPECT_TRUE(ranCleanly(runFacial({"render", model, "--size", "96x96", "--out", (dir / (tag + "_rest.png")).string()})));
    EXPECT_TRUE(ranCleanly(runFacial({"render", model, "--weight", "A=1", "--size", "96x96", "--out",
                                      (dir / (tag + "_A.png")).string()})));
    EXPECT_GT(differingFraction(readPngOrFail(dir / (tag + "_rest.png")), readPngOrFail(dir / (tag + "_A.png"))), 0.02);
  }
  EXPECT_TRUE(ranCleanly(runFacial({"sheet", "--model", vrmPath(1).string(), "--size", "64", "--out",
                                    (dir / "sheet.png").string()})));
}

TEST(FaceFormats, CandideMaskIsDrivenByItsActionUnitsAndShapedByShapeUnits) {
  FACIAL_REQUIRE_SHARED();
  const std::filesystem::path dir = testing_support::freshTempDir("face_formats_candide");
  const std::string mask = candidePath().string();
  for (const char* expression : {"neutral", "anger"})
    ASSERT_TRUE(ranCleanly(runFacial({"express", expression, "--model", mask, "--size", "128x128", "--out",
                                      (dir / (std::string(expression) + ".png")).string()})));
  const eng::Image neutral = readPngOrFail(dir / "neutral.png");
  // The mask is small in the frame (framed with every unit at full weight): brows and lids are a few hundred pixels.
  EXPECT_GT(differingFraction(neutral, readPngOrFail(dir / "anger.png")), 0.002);
  // The mask is drawn (bright skin in the middle, backdrop in the corner).
  const size_t centre = (size_t(64) * 128 + 64) * 4, corner = 0;
  EXPECT_GT(int(neutral.rgba8[centre]), int(neutral.rgba8[corner]) + 60);

  ASSERT_TRUE(ranCleanly(runFacial({"express", "neutral", "--model", mask, "--shape", "mouth width=1", "--shape",
                                    "SU_Eyes_width=1", "--size", "128x128", "--out", (dir / "shaped.png").string()})));
  EXPECT_GT(differingFraction(neutral, readPngOrFail(dir / "shaped.png")), 0.0015);

  const CommandOutput rig = runFacial({"rig", mask});
  ASSERT_EQ(rig.exitCode, 0) << rig.err;
  EXPECT_TRUE(contains(rig.out, "(CANDIDE-3): 52 morph weight(s)")) << rig.out;
  EXPECT_TRUE(contains(rig.out, "scheme: CANDIDE-3")) << rig.out;
}

TEST(FaceFormatsValidity, BadShapesBackgroundsAndUnknownFilesAreNamed) {
  const std::filesystem::path face = writeTestFace("face_formats_bad");
  const std::filesystem::path out = face.parent_path() / "x.png";
  const CommandOutput shape = runFacial({"express", "happy", "--model", face.string(), "--shape", "nose=1", "--out", out.string()});
  EXPECT_EQ(shape.exitCode, 1);
  EXPECT_TRUE(contains(shape.err, face.string() + ": --shape: no shape unit or morph target named 'nose'; available: "))
      << shape.err;
  const CommandOutput value = runFacial({"render", face.string(), "--shape", "custom_shape=lots", "--out", out.string()});
  EXPECT_EQ(value.exitCode, 1);
  EXPECT_TRUE(contains(value.err, "--shape 'custom_shape=lots' is not NAME=VALUE")) << value.err;
  const CommandOutput background = runFacial({"render", face.string(), "--background", "blue", "--out", out.string()});
  EXPECT_EQ(background.exitCode, 1);
  EXPECT_TRUE(contains(background.err, "--background 'blue' is not transparent, studio or a colour #RRGGBB"))
      << background.err;
  testing_support::writeFile(face.parent_path() / "notes.txt", "hello");
  const CommandOutput unknown = runFacial({"rig", (face.parent_path() / "notes.txt").string()});
  EXPECT_EQ(unknown.exitCode, 1);
  EXPECT_TRUE(contains(unknown.err, "notes.txt: not a face this program reads (glTF / GLB, VRM, FBX, a folder of OBJ"))
      << unknown.err;
  const CommandOutput missing = runFacial({"info", (face.parent_path() / "absent.vrm").string()});
  EXPECT_EQ(missing.exitCode, 1);
  EXPECT_TRUE(contains(missing.err, "absent.vrm: file not found")) << missing.err;
}

TEST(FaceFormats, ObjKeyframeFolderOpensWithoutConverting) {
  const std::filesystem::path dir = testing_support::freshTempDir("face_formats_obj");
  const eng::Model face = makeTestFace();
  const size_t weights = face.meshes[0].targetNames.size();
  int next = 0;
  testing_support::writeStudyObjSet(
      face, weights,
      [&](const char* name, std::vector<float>& w) {
        std::fill(w.begin(), w.end(), 0.0f);
        if (std::string(name) != "neutral") w[size_t(next++ % 4)] = 1.0f;
        return true;
      },
      dir / "set");
  testing_support::writeFile(dir / "map.json", testing_support::studyRigMapJson(1.0f));
  const CommandOutput rig = runFacial({"rig", (dir / "set").string(), "--rigmap", (dir / "map.json").string()});
  ASSERT_EQ(rig.exitCode, 0) << rig.err;
  EXPECT_TRUE(contains(rig.out, "(OBJ keyframe set): 6 morph weight(s), 6 driven")) << rig.out;
  EXPECT_TRUE(contains(rig.out, "emotion happy <- 'smile'")) << rig.out;
  EXPECT_TRUE(ranCleanly(runFacial({"express", "happy", "--model", (dir / "set").string(), "--rigmap",
                                    (dir / "map.json").string(), "--size", "64x64", "--out", (dir / "happy.png").string()})));
}

// The test face turned into a VRM 1.0 avatar: 'happy' binds the left smile
// target and turns the skin red; 'sad' is not defined (fear is composed).
// `edit` may change the VRMC_vrm extension before it is written.
std::filesystem::path writeTestVrm(const std::string& name,
                                   const std::function<void(nlohmann::json&)>& edit = {},
                                   const std::function<void(nlohmann::json&)>& editDocument = {}) {
  const std::filesystem::path glb = writeTestFace(name);
  auto bytes = eng::readFileBytes(glb, size_t{1} << 24);
  EXPECT_TRUE(bytes);
  auto chunks = eng::parseGlb(*bytes);
  EXPECT_TRUE(chunks);
  nlohmann::json json = nlohmann::json::parse(chunks->json.begin(), chunks->json.end());
  int faceNode = 0;
  for (size_t n = 0; n < json["nodes"].size(); ++n)
    if (json["nodes"][n].contains("mesh")) faceNode = int(n);
  json["extensionsUsed"] = {"VRMC_vrm"};
  json["extensions"]["VRMC_vrm"] = {
      {"specVersion", "1.0"},
      {"expressions",
       {{"preset",
         {{"happy",
           {{"morphTargetBinds", {{{"node", faceNode}, {"index", kSmileLeft}, {"weight", 1.0}}}},
            {"materialColorBinds", {{{"material", 0}, {"type", "color"}, {"targetValue", {1.0, 0.0, 0.0, 1.0}}}}}}},
          {"surprised", {{"morphTargetBinds", {{{"node", faceNode}, {"index", kJawDrop}, {"weight", 1.0}}}}}},
          {"neutral", nlohmann::json::object()}}}}}};
  if (edit) edit(json["extensions"]["VRMC_vrm"]);
  if (editDocument) editDocument(json);
  const std::string text = json.dump();
  const std::vector<uint8_t> vrm = eng::buildGlb(text, chunks->bin);
  const std::filesystem::path path = glb.parent_path() / "face.vrm";
  EXPECT_TRUE(eng::writeFileBytes(path, vrm.data(), vrm.size()));
  return path;
}

// `facial express` neutral and happy on `vrm` at 64x64 (empty images where it fails).
void expressNeutralAndHappy(const std::filesystem::path& vrm, eng::Image& neutral, eng::Image& happy) {
  const std::filesystem::path dir = vrm.parent_path();
  for (const char* expression : {"neutral", "happy"})
    ASSERT_TRUE(ranCleanly(runFacial({"express", expression, "--model", vrm.string(), "--size", "64x64", "--out",
                                      (dir / (std::string(expression) + ".png")).string()})));
  neutral = readPngOrFail(dir / "neutral.png");
  happy = readPngOrFail(dir / "happy.png");
}

TEST(FaceFormats, AnFbxCharacterOpensInInfoAndConvertsToGltf) {
  // Blender's FBX of a skinned face with two ARKit-named blend shapes (tests/importers/fbx).
  const std::filesystem::path fbx = testing_support::sourceDir() / "tests" / "importers" / "fbx" / "rigged_face.fbx";
  const CommandOutput info = runFacial({"info", fbx.string(), "--json"});
  ASSERT_EQ(info.exitCode, 0) << info.err;
  const nlohmann::json report = nlohmann::json::parse(info.out, nullptr, false);
  ASSERT_FALSE(report.is_discarded()) << info.out;
  EXPECT_EQ(report["meshes"][0]["targetNames"], nlohmann::json::array({"jawOpen", "mouthSmile_L"}));
  EXPECT_EQ(report["warnings"], nlohmann::json::array()) << "a sound file reads without a warning";

  const std::filesystem::path dir = testing_support::freshTempDir("face_formats_fbx");
  const CommandOutput converted = runFacial({"convert", fbx.string(), "--out", (dir / "face.glb").string()});
  ASSERT_EQ(converted.exitCode, 0) << converted.err;
  EXPECT_TRUE(contains(converted.out, "288 vertices, 2 morph target(s)")) << converted.out;
  auto glb = importers::loadFace(dir / "face.glb");
  ASSERT_TRUE(glb) << glb.error().message;
  EXPECT_EQ(glb->model.skins.size(), 1u) << "the skin is written with it";
  EXPECT_EQ(glb->model.meshes[0].targetNames, (std::vector<std::string>{"jawOpen", "mouthSmile_L"}));
}

TEST(FaceFormats, SyntheticVrmShowsMorphAndMaterialColourBinds) {
  const std::filesystem::path vrm = writeTestVrm("face_formats_synthetic_vrm");
  const CommandOutput rig = runFacial({"rig", vrm.string(), "--json"});
  ASSERT_EQ(rig.exitCode, 0) << rig.err;
  const nlohmann::json report = nlohmann::json::parse(rig.out, nullptr, false);
  ASSERT_FALSE(report.is_discarded()) << rig.out;
  EXPECT_EQ(report["format"], "VRM");
  EXPECT_EQ(report["drivenTargetCount"], 2);
  EXPECT_EQ(report["emotions"][1], "happy <- 'happy'");
  EXPECT_EQ(report["emotions"][4], "fear <- 'surprised' x0.55 (composed)");
  eng::Image neutral, happy;
  expressNeutralAndHappy(vrm, neutral, happy);
  ASSERT_FALSE(neutral.rgba8.empty());
  ASSERT_FALSE(happy.rgba8.empty());
  const size_t centre = (size_t(32) * 64 + 32) * 4;
  EXPECT_GT(int(happy.rgba8[centre]) - int(happy.rgba8[centre + 1]), 100) << "the skin turns red";
  EXPECT_LT(int(neutral.rgba8[centre]) - int(neutral.rgba8[centre + 1]), 80);
  EXPECT_GT(differingFraction(neutral, happy), 0.2);
}

TEST(FaceFormats, VrmShadeColourBindRecoloursAToonSkin) {
  // The skin is MToon, shifted all into shade (grey); 'happy' binds the shade
  // colour to blue: the happy face is blue where the neutral one is grey.
  const std::filesystem::path vrm = writeTestVrm(
      "face_formats_vrm_toon",
      [](nlohmann::json& ext) {
        ext["expressions"]["preset"]["happy"]["materialColorBinds"] =
            nlohmann::json::array({{{"material", 0}, {"type", "shadeColor"}, {"targetValue", {0.0, 0.0, 1.0, 1.0}}}});
      },
      [](nlohmann::json& doc) {
        doc["materials"][0]["extensions"]["VRMC_materials_mtoon"] = {
            {"specVersion", "1.0"}, {"shadeColorFactor", {0.5, 0.5, 0.5}}, {"shadingShiftFactor", -1.0}};
        doc["extensionsUsed"].push_back("VRMC_materials_mtoon");
      });
  eng::Image neutral, happy;
  expressNeutralAndHappy(vrm, neutral, happy);
  ASSERT_FALSE(neutral.rgba8.empty());
  ASSERT_FALSE(happy.rgba8.empty());
  const size_t centre = (size_t(32) * 64 + 32) * 4;
  EXPECT_LT(std::abs(int(neutral.rgba8[centre + 2]) - int(neutral.rgba8[centre])), 40) << "grey shade";
  EXPECT_GT(int(happy.rgba8[centre + 2]) - int(happy.rgba8[centre]), 60) << "blue shade";
}

// Red minus green at the image centre: how far the skin has turned red.
int redness(const eng::Image& image) {
  const size_t centre = (size_t(image.height / 2) * size_t(image.width) + size_t(image.width / 2)) * 4;
  return int(image.rgba8[centre]) - int(image.rgba8[centre + 1]);
}

// The animated path: `play` drives the material colour bind frame by frame
// with the expression weight (neutral, then a linear 1 s blend to happy).
TEST(FaceFormats, SyntheticVrmMaterialColourFollowsTheAnimatedWeightInPlay) {
  const std::filesystem::path vrm = writeTestVrm("face_formats_vrm_play");
  const std::filesystem::path dir = vrm.parent_path();
  testing_support::writeFile(dir / "to_happy.json", R"({"version": 1, "channels": "actionUnits",
    "root": {"type": "stateMachine", "defaultState": "neutral", "states": [
      {"name": "neutral", "node": {"type": "pose", "preset": "neutral"},
       "transitions": [{"to": "happy", "duration": 1.0, "curve": "linear", "exitTime": 0.5}]},
      {"name": "happy", "node": {"type": "pose", "preset": "happy"}}]}})");
  ASSERT_TRUE(ranCleanly(runFacial({"play", (dir / "to_happy.json").string(), "--model", vrm.string(), "--fps", "4",
                                    "--seconds", "2.25", "--size", "64x64", "--out", (dir / "frames").string()})));
  // Frames at 0 s (neutral), 1 s (halfway) and 2 s (happy).
  const eng::Image neutral = readPngOrFail(dir / "frames" / "frame_0000.png");
  const eng::Image halfway = readPngOrFail(dir / "frames" / "frame_0004.png");
  const eng::Image happy = readPngOrFail(dir / "frames" / "frame_0008.png");
  ASSERT_FALSE(neutral.rgba8.empty() || halfway.rgba8.empty() || happy.rgba8.empty());
  EXPECT_LT(redness(neutral), 80) << "the skin's own colour";
  EXPECT_GT(redness(happy), 100) << "the bind's red";
  EXPECT_GT(redness(halfway), redness(neutral) + 15) << "halfway is redder than neutral";
  EXPECT_LT(redness(halfway), redness(happy) - 15) << "and less red than happy";
  // The same pose through `express` draws the same colour: one path for still and animated views.
  ASSERT_TRUE(ranCleanly(runFacial({"express", "happy", "--model", vrm.string(), "--size", "64x64", "--zoom", "1.15",
                                    "--out", (dir / "express_happy.png").string()})));
  EXPECT_NEAR(redness(readPngOrFail(dir / "express_happy.png")), redness(happy), 12);
}

// The demo's headless tour (neutral, then happy from 2.4 s, fully at 3.2 s)
// drives the same per-instance material records.
TEST(FaceFormats, SyntheticVrmMaterialColourFollowsTheHeadlessDemoTour) {
  const std::filesystem::path vrm = writeTestVrm("face_formats_vrm_demo");
  const std::filesystem::path out = vrm.parent_path() / "tour";
  ASSERT_TRUE(ranCleanly(runFacial({"demo", "--headless", "--model", vrm.string(), "--size", "48x48", "--fps", "2",
                                    "--seconds", "4.5", "--out", out.string()})));
  const eng::Image neutral = readPngOrFail(out / "frames" / "frame_0000.png");
  const eng::Image happy = readPngOrFail(out / "frames" / "frame_0008.png");  // 4 s
  ASSERT_FALSE(neutral.rgba8.empty() || happy.rgba8.empty());
  EXPECT_LT(redness(neutral), 80);
  EXPECT_GT(redness(happy), 100);
}

// The contact sheet poses every preset with its material binds too.
TEST(FaceFormats, SyntheticVrmSheetTilesShowTheMaterialBind) {
  const std::filesystem::path vrm = writeTestVrm("face_formats_vrm_sheet");
  const std::filesystem::path sheet = vrm.parent_path() / "sheet.png";
  ASSERT_TRUE(ranCleanly(runFacial({"sheet", "--model", vrm.string(), "--size", "64", "--out", sheet.string()})));
  const eng::Image image = readPngOrFail(sheet);
  ASSERT_FALSE(image.rgba8.empty());
  size_t red = 0;
  for (size_t p = 0; p < image.rgba8.size(); p += 4) red += int(image.rgba8[p]) - int(image.rgba8[p + 1]) > 100 ? 1 : 0;
  EXPECT_GT(red, 64u * 64u / 4) << "the happy tile is red";
}

// A material bind that cannot be applied is left out with one warning line
// naming the file and the bind; the avatar still loads and plays its other binds.
TEST(FaceFormatsValidity, BadVrmMaterialBindsWarnOnceAndTheFaceStillRenders) {
  const std::filesystem::path vrm = writeTestVrm("face_formats_vrm_bad_bind", [](nlohmann::json& ext) {
    auto& happy = ext["expressions"]["preset"]["happy"];
    happy["materialColorBinds"].push_back({{"material", 7}, {"type", "color"}, {"targetValue", {0, 1, 0, 1}}});
    happy["materialColorBinds"].push_back({{"material", 0}, {"type", "color"}, {"targetValue", {0, nullptr, 0, 1}}});
  });
  const std::filesystem::path png = vrm.parent_path() / "happy.png";
  const CommandOutput run =
      runFacial({"express", "happy", "--model", vrm.string(), "--size", "64x64", "--out", png.string()});
  ASSERT_TRUE(ranCleanly(run));
  const std::string outOfRange = vrm.string() +
                                 ": /extensions/VRMC_vrm/expressions/preset/happy/materialColorBinds/1/material: 7 is "
                                 "out of range (1 materials); bind ignored";
  const std::string notFinite = vrm.string() +
                                ": /extensions/VRMC_vrm/expressions/preset/happy/materialColorBinds/2/targetValue/1: "
                                "must be a finite number, got null; bind ignored";
  for (const std::string& line : {outOfRange, notFinite}) {
    const size_t at = run.err.find(line);
    EXPECT_NE(at, std::string::npos) << run.err;
    EXPECT_EQ(run.err.find(line, at + 1), std::string::npos) << "said once: " << run.err;
  }
  EXPECT_GT(redness(readPngOrFail(png)), 100) << "the good bind still turns the skin red";
}

// Alpha from coverage, colour un-premultiplied: edge pixels keep the colour of
// the surface next to them instead of fading to black.
TEST(FaceFormats, TransparentBackgroundHasCleanAlphaEdges) {
  const std::filesystem::path face = writeTestFace("face_formats_alpha");
  const std::filesystem::path png = face.parent_path() / "alpha.png";
  ASSERT_TRUE(ranCleanly(runFacial({"render", face.string(), "--background", "transparent", "--zoom", "0.6",
                                    "--yaw", "20", "--size", "160x160", "--out", png.string()})));
  const eng::Image image = readPngOrFail(png);
  ASSERT_EQ(image.width, 160);
  auto at = [&](int x, int y) { return image.rgba8.data() + (size_t(y) * 160 + x) * 4; };
  EXPECT_EQ(at(0, 0)[3], 0);
  EXPECT_EQ(at(159, 159)[3], 0);
  EXPECT_EQ(at(80, 80)[3], 255);
  size_t edge = 0, dark = 0;
  for (int y = 1; y < 159; ++y)
    for (int x = 1; x < 159; ++x) {
      const uint8_t* p = at(x, y);
      if (p[3] == 0 || p[3] == 255) continue;
      // The brightest opaque neighbour within two pixels.
      int neighbour = -1;
      for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx) {
          if (x + dx < 0 || x + dx >= 160 || y + dy < 0 || y + dy >= 160) continue;
          const uint8_t* q = at(x + dx, y + dy);
          if (q[3] == 255) neighbour = std::max(neighbour, int(q[0]) + q[1] + q[2]);
        }
      if (neighbour < 0) continue;
      ++edge;
      if (int(p[0]) + p[1] + p[2] < neighbour * 0.6) ++dark;
    }
  EXPECT_GT(edge, 40u) << "the silhouette should be anti-aliased";
  EXPECT_LT(dark, edge / 20 + 1) << dark << " of " << edge << " edge pixels are much darker than the surface";
}

TEST(FaceFormats, SolidBackgroundColourAndTransparentSheet) {
  const std::filesystem::path face = writeTestFace("face_formats_solid");
  const std::filesystem::path png = face.parent_path() / "solid.png";
  ASSERT_TRUE(ranCleanly(runFacial({"express", "happy", "--model", face.string(), "--background", "#20a0ff", "--zoom",
                                    "0.6", "--size", "64x64", "--out", png.string()})));
  const eng::Image image = readPngOrFail(png);
  ASSERT_FALSE(image.rgba8.empty());
  EXPECT_NEAR(image.rgba8[0], 0x20, 2);
  EXPECT_NEAR(image.rgba8[1], 0xa0, 2);
  EXPECT_NEAR(image.rgba8[2], 0xff, 2);
  EXPECT_EQ(image.rgba8[3], 255);

  const std::filesystem::path sheet = face.parent_path() / "sheet.png";
  ASSERT_TRUE(ranCleanly(runFacial({"sheet", "--model", face.string(), "--background", "transparent", "--size", "48",
                                    "--out", sheet.string()})));
  const eng::Image tiles = readPngOrFail(sheet);
  ASSERT_FALSE(tiles.rgba8.empty());
  EXPECT_EQ(tiles.rgba8[3], 0);  // the sheet's own background
  size_t opaque = 0;
  for (size_t p = 3; p < tiles.rgba8.size(); p += 4) opaque += tiles.rgba8[p] == 255 ? 1 : 0;
  EXPECT_GT(opaque, 7u * 48 * 10) << "faces and labels stay opaque";
}

}  // namespace
}  // namespace cli_test
