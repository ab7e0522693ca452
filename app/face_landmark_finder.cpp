#include "app/face_landmark_finder.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>

#include "app/headless_model_renderer.h"
#include "autorig/face_frame.h"
#include "autorig/surface_cast.h"
#include "engine/scene/image_io.h"
#include "engine/scene/weights.h"
#include "engine/view/framing_bounds.h"

namespace app {

namespace {

std::string modelName(const eng::Model& model) { return model.sourcePath.empty() ? "the model" : model.sourcePath; }

void drawDot(eng::Image& image, glm::vec2 centre, int radius, glm::u8vec4 colour) {
  const glm::ivec2 c = glm::ivec2(glm::floor(centre));
  for (int y = c.y - radius; y <= c.y + radius; ++y)
    for (int x = c.x - radius; x <= c.x + radius; ++x) {
      if (x < 0 || y < 0 || x >= image.width || y >= image.height) continue;
      if ((x - c.x) * (x - c.x) + (y - c.y) * (y - c.y) > radius * radius) continue;
      uint8_t* p = &image.rgba8[(size_t(y) * size_t(image.width) + size_t(x)) * 4];
      p[0] = colour.r, p[1] = colour.g, p[2] = colour.b, p[3] = 255;
    }
}

// Detected points green, the cast points projected back red (drawn smaller,
// on top): where red leaves its green ring the cast moved the point.
eng::Result<void> writePicture(eng::Image image, const autorig::DetectedFace& face,
                               const autorig::FaceLandmarks& landmarks, const autorig::SurfaceCaster& caster,
                               const std::filesystem::path& path) {
  const int radius = std::max(1, image.width / 160);
  for (const glm::vec2& p : face.pixels) drawDot(image, p, radius, {40, 220, 60, 255});
  for (const glm::vec3& p : landmarks.points)
    if (auto s = caster.project(p)) drawDot(image, *s, radius / 2, {230, 30, 30, 255});
  return eng::writePng(path, image.width, image.height, image.rgba8);
}

// How far from its pixel a point may be taken from the surface, of the
// picture's side: dlib puts the jaw line on the face's outline, which a face
// cut out as a mask may not reach, and a lid point inside the eye opening
// goes to the rim, a few vertices away on a coarse mesh.
constexpr float kReach = 0.04f;

std::string describe(const autorig::DetectedFace& face) {
  char text[128];
  if (std::isfinite(face.confidence))
    std::snprintf(text, sizeof text, "dlib (face box %.0f px, confidence %.2f)", double(face.box.max.x - face.box.min.x),
                  double(face.confidence));
  else
    std::snprintf(text, sizeof text, "%s (%.0f px): no face detected", std::string(kFittedInTheTargetsBox).c_str(),
                  double(face.box.max.x - face.box.min.x));
  return text;
}

struct Sighting {
  eng::Image image;
  autorig::DetectedFace face;
};

// One picture from the renderer's camera and the face dlib finds in it.
eng::Result<std::optional<Sighting>> look(HeadlessModelRenderer& renderer, std::span<const float> weights,
                                          const autorig::LandmarkDetector& detector) {
  auto image = renderer.render(weights);
  if (!image) return image.error();
  ENG_TRY(renderer.checkValidation());
  std::optional<autorig::DetectedFace> face = detector.detect(*image);
  if (!face) return std::optional<Sighting>();
  return std::optional<Sighting>(Sighting{std::move(*image), *face});
}

// The face framing shows head and neck (a full-body avatar's face can be a
// fifth of the picture): the camera moves in until the face box is about
// 60 % of the picture wide, centred, so the predictor sees the features in
// detail and the jaw line still fits.
// False when the face is that big already.
bool closeIn(eng::OrbitCamera& camera, const autorig::PixelBox& box, float size) {
  const float k = std::min(0.6f * size / std::max(box.max.x - box.min.x, 1.0f), 4.0f);
  if (k < 1.15f) return false;
  const glm::vec2 centre = (box.min + box.max) / size - 1.0f;  // NDC, y down
  camera.zoom *= k;
  camera.imageCentre = (camera.imageCentre - centre) * k;
  return true;
}

// `placement`: where the renderer stands the model (HeadlessModelRenderer::place).
autorig::PictureCamera pictureCamera(const eng::OrbitCamera& camera, uint32_t size,
                                     const glm::mat4& placement = glm::mat4(1.0f)) {
  return {camera.projection(1.0f) * camera.view() * placement, glm::vec2(float(size))};
}

// Where the face must be when dlib's detector misses it (a stylised face):
// the square around the region its morph targets move, seen from the
// camera. Nullopt unless that region is on the camera's side of the head
// (a face turned away is no face) or when nothing morphs.
std::optional<autorig::PixelBox> targetsBox(const eng::Model& model, const eng::OrbitCamera& camera, uint32_t size) {
  const eng::Aabb features = eng::faceFeatureBounds(model);
  const eng::Aabb head = eng::framingBounds(model, eng::FramingMode::Face);
  if (!features.valid() || !head.valid()) return std::nullopt;
  const glm::vec3 toCamera = glm::normalize(camera.position() - camera.target);
  if (glm::dot(features.center() - head.center(), toCamera) < 0.1f * glm::dot(glm::abs(head.size()), glm::abs(toCamera)))
    return std::nullopt;
  autorig::PixelBox box{glm::vec2(INFINITY), glm::vec2(-INFINITY)};
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 p(corner & 1 ? features.max.x : features.min.x, corner & 2 ? features.max.y : features.min.y,
                      corner & 4 ? features.max.z : features.min.z);
    const std::optional<glm::vec2> s = autorig::projectToPicture(pictureCamera(camera, size), p);
    if (!s) return std::nullopt;
    box.min = glm::min(box.min, *s), box.max = glm::max(box.max, *s);
  }
  const glm::vec2 centre = (box.min + box.max) * 0.5f;
  const float half = 0.5f * std::max(box.max.x - box.min.x, box.max.y - box.min.y);
  return autorig::PixelBox{centre - half, centre + half};
}

// The detector missed: closer in on the targets' region and look again;
// still nothing, and the predictor is fitted in that box.
eng::Result<std::optional<Sighting>> lookWhereTheTargetsAre(const eng::Model& model, HeadlessModelRenderer& renderer,
                                                            std::span<const float> weights,
                                                            const autorig::LandmarkDetector& detector, uint32_t size) {
  eng::OrbitCamera& camera = renderer.view().camera;
  std::optional<autorig::PixelBox> box = targetsBox(model, camera, size);
  if (!box) return std::optional<Sighting>();
  if (closeIn(camera, *box, float(size))) {
    std::optional<Sighting> seen = ENG_TRY_VALUE(look(renderer, weights, detector));
    if (seen) return seen;
    box = targetsBox(model, camera, size);
    if (!box) return std::optional<Sighting>();
  }
  auto image = renderer.render(weights);
  if (!image) return image.error();
  autorig::DetectedFace face = detector.fit(*image, *box);
  return std::optional<Sighting>(Sighting{std::move(*image), face});
}

// The inner lips (60-67) and the outer lip point in front of each (the
// corners for 60 and 64).
constexpr std::array<size_t, 8> kOuterLipBefore = {48, 50, 51, 52, 54, 56, 57, 58};

// How deep an inner-lip point may lie: a lip's inner rim is less than a fifth
// of the mouth's width behind its outer edge. A ray between parted lips that
// meets the mouth's back wall (facecap's inside faces the camera) went through
// the opening: the rim is meant, as for a lid over an eye's opening. Infinity
// until the outer lips are on the surface.
float innerLipDepthLimit(const autorig::SurfaceCaster& caster, const autorig::FaceLandmarks& landmarks, size_t i) {
  if (i < 60 || i > 67) return std::numeric_limits<float>::infinity();
  const auto& p = landmarks.points;
  const float width = glm::distance(p[48], p[54]);
  const glm::vec3& before = p[kOuterLipBefore[i - 60]];
  if (!std::isfinite(width) || !std::isfinite(before.x)) return std::numeric_limits<float>::infinity();
  return caster.depth(before) + 0.2f * width;
}

// How deep an eye corner (36, 39; 42, 45) may lie: a quarter of the brows'
// width (17 to 26) behind the brow's end above it. A ray through the far
// eye's outer corner of a face turned aside that slips between the lid and
// the ball meets the inside of the head behind it: facecap turned 20 degrees
// had its point 45 a head's depth back, its face's forward taken 56 degrees
// aside, and its points found again from there on a face turned the other
// way. Infinity until the brows are on the surface.
float eyeCornerDepthLimit(const autorig::SurfaceCaster& caster, const autorig::FaceLandmarks& landmarks, size_t i) {
  size_t brow = 0;
  switch (i) {
    case 36: brow = 17; break;
    case 39: brow = 21; break;
    case 42: brow = 22; break;
    case 45: brow = 26; break;
    default: return std::numeric_limits<float>::infinity();
  }
  const auto& p = landmarks.points;
  const float width = glm::distance(p[17], p[26]);
  const float above = caster.depth(p[brow]);
  if (!std::isfinite(width) || !std::isfinite(above)) return std::numeric_limits<float>::infinity();
  return above + 0.25f * width;
}

// How deep a lid point (37, 38, 40, 41; 43, 44, 46, 47) may lie: no deeper
// than the line between its eye's corners at its place, and a twentieth of
// the eye's width. A lid bulges over the ball in front of that line; a ray
// through the opening that meets the inside of a closed socket (Ready Player
// Me's faces have no hole at the eyes) found a point 10 mm behind the lid,
// which the warp then dragged the source's lid towards. Infinity until the
// corners are on the surface.
float lidDepthLimit(const autorig::SurfaceCaster& caster, const autorig::FaceLandmarks& landmarks, glm::vec2 pixel,
                    size_t i) {
  const bool right = i >= 37 && i <= 41 && i != 39, left = i >= 43 && i <= 47 && i != 45;
  if (!right && !left) return std::numeric_limits<float>::infinity();
  const glm::vec3& a = landmarks.points[right ? 36 : 42];
  const glm::vec3& b = landmarks.points[right ? 39 : 45];
  const std::optional<glm::vec2> pa = caster.project(a), pb = caster.project(b);
  if (!pa || !pb || !std::isfinite(a.x) || !std::isfinite(b.x)) return std::numeric_limits<float>::infinity();
  const glm::vec2 across = *pb - *pa;
  const float span = glm::dot(across, across);
  const float t = span > 0.0f ? std::clamp(glm::dot(pixel - *pa, across) / span, 0.0f, 1.0f) : 0.5f;
  return glm::mix(caster.depth(a), caster.depth(b), t) + 0.05f * glm::distance(a, b);
}

// How deep a jaw-line point (1-15) may lie: a fifth of the face's width
// (0 to 16) deeper than its neighbour towards the ear, the jaw coming forward
// from the ears to the chin. dlib puts these points on the face's outline,
// and a ray just past an untextured jaw meets the neck behind it: a point
// there bent the warped jaw back into the neck. Infinity until the
// neighbours are on the surface.
float jawLineDepthLimit(const autorig::SurfaceCaster& caster, const autorig::FaceLandmarks& landmarks, size_t i) {
  if (i < 1 || i > 15) return std::numeric_limits<float>::infinity();
  const auto& p = landmarks.points;
  const float width = glm::distance(p[0], p[16]);
  float neighbour = i < 8 ? caster.depth(p[i - 1]) : i > 8 ? caster.depth(p[i + 1]) : 0.0f;
  if (i == 8) neighbour = std::max(caster.depth(p[7]), caster.depth(p[9]));
  if (!std::isfinite(width) || !std::isfinite(neighbour)) return std::numeric_limits<float>::infinity();
  return neighbour + 0.2f * width;
}

// A jaw-line point (1-15) that came out far deeper than the line between its
// neighbours (more than a fifth of the face's width: the ray at the outline
// went past the jaw onto the ear or the side of the head behind it, as the
// built-in head turned 20 degrees showed its point 1, 7 cm back) is cast
// again no deeper than that line plus a tenth of the width. Where nothing is
// in front of that bound, it stays.
void pullJawLineOntoTheJaw(const autorig::SurfaceCaster& caster, const Sighting& seen, uint32_t size,
                           autorig::FaceLandmarks& landmarks) {
  auto& p = landmarks.points;
  const float width = glm::distance(p[0], p[16]);
  if (!std::isfinite(width)) return;
  for (size_t i = 1; i < 16; ++i) {
    const float between = 0.5f * (caster.depth(p[i - 1]) + caster.depth(p[i + 1]));
    if (!std::isfinite(between) || !(caster.depth(p[i]) > between + 0.2f * width)) continue;
    if (auto hit = caster.cast(seen.face.pixels[i], kReach * float(size), between + 0.1f * width)) p[i] = hit->position;
  }
}

// The order points are cast in: the jaw line from the ears to the chin (each
// point's depth bounded by the one before it), each eye's corners before its
// lids (whose depth they bound), the outer lips before the inner ones (as
// numbered).
constexpr std::array<size_t, autorig::kLandmarkCount> kCastOrder = [] {
  std::array<size_t, autorig::kLandmarkCount> order{};
  size_t n = 0;
  for (size_t i = 0; i < 8; ++i) order[n++] = i, order[n++] = 16 - i;
  order[n++] = 8;
  for (size_t i = 17; i < 36; ++i) order[n++] = i;
  for (size_t i : {36, 39, 42, 45, 37, 38, 40, 41, 43, 44, 46, 47}) order[n++] = i;
  for (size_t i = 48; i < autorig::kLandmarkCount; ++i) order[n++] = i;
  return order;
}();

// Each detected pixel cast onto the face; the first that misses is named.
eng::Result<autorig::FaceLandmarks> castOntoFace(const autorig::SurfaceCaster& caster, const Sighting& seen,
                                                 uint32_t size, const std::string& name,
                                                 const std::filesystem::path& picture) {
  autorig::FaceLandmarks landmarks;
  landmarks.source = describe(seen.face);
  std::optional<size_t> missed;
  for (const size_t i : kCastOrder) {
    const float limit = std::min({innerLipDepthLimit(caster, landmarks, i), eyeCornerDepthLimit(caster, landmarks, i),
                                  lidDepthLimit(caster, landmarks, seen.face.pixels[i], i),
                                  jawLineDepthLimit(caster, landmarks, i)});
    std::optional<autorig::SurfacePoint> hit = caster.cast(seen.face.pixels[i], kReach * float(size), limit);
    if (!hit && std::isfinite(limit))  // nothing in front of the limit: a deep point rigs better than none
      hit = caster.cast(seen.face.pixels[i], kReach * float(size), std::numeric_limits<float>::infinity());
    if (hit) landmarks.points[i] = hit->position;
    else if (!missed) missed = i, landmarks.points[i] = glm::vec3(NAN);
  }
  if (!missed) pullJawLineOntoTheJaw(caster, seen, size, landmarks);
  if (!picture.empty()) ENG_TRY(writePicture(seen.image, seen.face, landmarks, caster, picture));
  if (missed)
    return eng::makeError(eng::ErrorKind::NotFound, name + ": landmark " + std::to_string(*missed) +
                                                        " of the front view is not on the face's surface");
  return landmarks;
}

// A face turned from the camera (a scan as it was captured, a head turned on
// its neck) has its jaw line found on its outline, away from where a front
// view puts it, and the warp carries the source's front-view points there:
// the far cheek creased in every expression. Once found, the face is looked
// at again from the front its own points give: square to its eyes (yaw),
// and within kPitchSlack of the pitch a face seen level has (its eyes are
// set back from its chin).
constexpr float kYawSlack = 5.0f, kPitchSlack = 8.0f;  // degrees

// dlib's detector finds faces turned up to about 35° from it: one turned
// further is looked for from either side, above and below, and from the
// four corners between them (yaw, pitch degrees: a face looking 45° aside
// and 30° up is seen from none of the four straight ones), and then from its
// own front. A face seen from the back is not.
constexpr std::array<glm::vec2, 4> kStraightSideViews = {{{-30.0f, 0.0f}, {30.0f, 0.0f}, {0.0f, 25.0f}, {0.0f, -25.0f}}};
constexpr std::array<glm::vec2, 4> kCornerViews = {{{-30.0f, 25.0f}, {30.0f, 25.0f}, {-30.0f, -25.0f}, {30.0f, -25.0f}}};

// The camera turned to face the face, or nullopt when it faces it already.
// `placement`: where the renderer stands the model.
std::optional<eng::OrbitCamera> facingTheFace(const eng::OrbitCamera& camera, const autorig::FaceLandmarks& landmarks,
                                              const glm::mat4& placement) {
  const glm::vec3 forward = glm::normalize(glm::mat3(placement) * autorig::LandmarkFrame(landmarks).forward());
  if (!std::isfinite(forward.x) || !std::isfinite(forward.y) || !std::isfinite(forward.z)) return std::nullopt;
  const float yaw = glm::degrees(std::atan2(forward.x, forward.z));
  const float pitch = glm::degrees(std::asin(std::clamp(forward.y, -1.0f, 1.0f)));
  eng::OrbitCamera turned = camera;
  if (std::abs(yaw - camera.yawDegrees) > kYawSlack) turned.yawDegrees = yaw;
  if (std::abs(pitch - kLevelPitchDegrees - camera.pitchDegrees) > kPitchSlack) turned.pitchDegrees = pitch - kLevelPitchDegrees;
  if (turned.yawDegrees == camera.yawDegrees && turned.pitchDegrees == camera.pitchDegrees) return std::nullopt;
  return turned;
}

struct Seen {
  autorig::FaceLandmarks landmarks;
  float confidence = NAN;  // dlib's detector's; NaN when only fitted in the targets' box
  bool detected() const { return std::isfinite(confidence); }
};

// A face that is not upright and facing +Z in its file (a Z-up export, a
// scan as it was captured, a head looking sideways or away) is looked for
// with the model stood in each of the other 23 quarter-turn orientations,
// those turning it about the vertical first. Its front and top: the model's
// axes that face the camera and point up.
struct QuarterTurn {
  glm::vec3 front, top;
  glm::mat3 rotation() const { return standingUpRotation(front, top); }
};

const std::vector<QuarterTurn>& quarterTurns() {
  static const std::vector<QuarterTurn> turns = [] {
    const std::array<glm::vec3, 6> axes = {{{1, 0, 0}, {-1, 0, 0}, {0, 0, -1}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}}};
    std::vector<QuarterTurn> all;
    for (const glm::vec3& top : {glm::vec3(0, 1, 0), glm::vec3(0, 0, 1), glm::vec3(0, 0, -1), glm::vec3(1, 0, 0),
                                 glm::vec3(-1, 0, 0), glm::vec3(0, -1, 0)})
      for (const glm::vec3& front : axes)
        if (glm::dot(front, top) == 0.0f && !(front.z == 1.0f && top.y == 1.0f)) all.push_back({front, top});
    return all;
  }();
  return turns;
}

// A file stands its model up along +Y (glTF) or +Z (a Z-up export); a face
// turned between those axes as well (a scan captured looking aside and
// down) is in no quarter turn's straight view, and is looked for from the
// corners of the quarter turns that keep its top up.
bool keepsTheFilesTopUp(const QuarterTurn& turn) { return turn.top.y == 1.0f || turn.top.z == 1.0f; }


// The model's framing box turned (about the origin): the camera frames the
// turned model about as it frames one upright in its file.
eng::OrbitCamera turnedFraming(const eng::Aabb& box, const glm::mat3& rotation) {
  eng::Aabb turned;
  for (int corner = 0; corner < 8; ++corner)
    turned.extend(rotation * glm::vec3(corner & 1 ? box.max.x : box.min.x, corner & 2 ? box.max.y : box.min.y,
                                       corner & 4 ? box.max.z : box.min.z));
  return eng::OrbitCamera::frame(turned, 1.0f);
}

// Exactly as it frames the model stood upright in its file: the head's box
// is found along the file's axes (eng::framingBounds), so the turned box is
// not it, and the jaw line, the face's outline, moves with the framing.
eng::OrbitCamera uprightFraming(const eng::Model& model, const glm::mat3& rotation) {
  eng::Model upright;  // all framingBounds reads; not the images
  upright.nodes = model.nodes, upright.roots = model.roots, upright.meshes = model.meshes;
  upright.skins = model.skins, upright.humanoidHead = model.humanoidHead;
  eng::turnAtRoots(upright, glm::quat_cast(rotation));
  return eng::OrbitCamera::frame(eng::framingBounds(upright, eng::FramingMode::Face), 1.0f);
}

// From the renderer's camera: the face dlib finds, looked at closer when it
// is small in the picture, its points cast onto the face. Nullopt when no
// face is seen, or when one of its points misses the surface (a face seen
// at a slant, its outline past the mesh): `missed` keeps the first such line
// ("x.glb: landmark 24 ... is not on the face's surface") for when no view
// does better.
eng::Result<std::optional<Seen>> landmarksSeen(const eng::Model& model, const autorig::PosedFace& posed,
                                                                 HeadlessModelRenderer& renderer,
                                                                 std::span<const float> weights,
                                                                 const autorig::LandmarkDetector& detector,
                                                                 const FaceLandmarkOptions& options,
                                                                 bool fitInTheTargetsBox, std::string& missed) {
  std::optional<Sighting> seen = ENG_TRY_VALUE(look(renderer, weights, detector));
  if (!seen && fitInTheTargetsBox)
    seen = ENG_TRY_VALUE(lookWhereTheTargetsAre(model, renderer, weights, detector, options.size));
  if (!seen) return std::optional<Seen>();
  eng::OrbitCamera& camera = renderer.view().camera;
  const eng::OrbitCamera wide = camera;
  if (std::isfinite(seen->face.confidence) && closeIn(camera, seen->face.box, float(options.size))) {
    std::optional<Sighting> close = ENG_TRY_VALUE(look(renderer, weights, detector));
    if (close) seen = std::move(close);
    else camera = wide;
  }
  const autorig::PictureCamera picture = pictureCamera(camera, options.size, renderer.placement());
  const autorig::SurfaceCaster caster(model, posed, autorig::seenSkinPrimitives(model, posed, picture), picture);
  auto cast = castOntoFace(caster, *seen, options.size, modelName(model), options.picture);
  if (!cast) {
    if (cast.error().kind != eng::ErrorKind::NotFound) return cast.error();
    if (missed.empty()) missed = cast.error().message;
    return std::optional<Seen>();
  }
  return std::optional<Seen>(Seen{std::move(*cast), seen->face.confidence});
}

}  // namespace

glm::mat3 levelRotation(const autorig::FaceLandmarks& landmarks) {
  const autorig::LandmarkFrame frame(landmarks);
  const glm::mat3 level = glm::mat3(glm::angleAxis(glm::radians(-kLevelPitchDegrees), glm::vec3(1, 0, 0)));
  return level * glm::transpose(glm::mat3(frame.side(), frame.up(), frame.forward()));
}

glm::mat3 standingUpRotation(const glm::vec3& front, const glm::vec3& top) {
  // Rows: where each file axis goes.
  return glm::transpose(glm::mat3(glm::cross(top, front), top, front));
}

std::string directionName(const glm::vec3& direction) {
  char text[64];
  std::snprintf(text, sizeof text, "(%.2f, %.2f, %.2f)", double(direction.x), double(direction.y), double(direction.z));
  return text;
}

std::string signedAxisName(const glm::vec3& axis) {
  const char* sign = axis.x + axis.y + axis.z > 0.0f ? "+" : "-";
  return sign + std::string(axis.x != 0.0f ? "X" : axis.y != 0.0f ? "Y" : "Z");
}

eng::Result<autorig::FaceLandmarks> findFaceLandmarks(const eng::Model& model, const autorig::PosedFace& posed,
                                                      const FaceLandmarkOptions& options) {
  const std::string name = modelName(model);
  if (posed.vertexCount() == 0)
    return eng::makeError(eng::ErrorKind::InvalidArgument, name + ": nothing is drawn, so there is no face to find");
  if (options.size < 128 || options.size > 4096)
    return eng::makeError(eng::ErrorKind::InvalidArgument, "the landmark picture's size must be 128 to 4096 pixels");
  auto detector = autorig::LandmarkDetector::shared(options.predictor);
  if (!detector) return detector.error();
  const eng::Model& drawn = options.display ? *options.display : model;
  auto renderer = HeadlessModelRenderer::create(
      drawn, {.width = options.size, .height = options.size, .quality = eng::vk::RenderQuality::Fast});
  if (!renderer) return renderer.error();
  const std::vector<float> weights = eng::WeightLayout(drawn).defaults();
  eng::OrbitCamera& camera = renderer->view().camera;
  const eng::OrbitCamera front = camera;
  std::string missed;  // the first view whose points missed the surface
  auto seenNow = [&](bool fitInTheTargetsBox) {
    return landmarksSeen(model, posed, *renderer, weights, **detector, options, fitInTheTargetsBox, missed);
  };
  std::optional<Seen> found = ENG_TRY_VALUE(seenNow(true));
  if (!found || !found->detected()) {
    // Of the side views, the one the detector is surest of (the view turned away from the face
    // sees it nearly in profile, where the points are a guess); else the points fitted in the
    // targets' box from the front.
    for (const auto* views : {&kStraightSideViews, &kCornerViews})
      for (const glm::vec2& turn : *views) {
        camera = front;
        camera.yawDegrees += turn.x, camera.pitchDegrees += turn.y;
        std::optional<Seen> side = ENG_TRY_VALUE(seenNow(false));
        if (side && (!found || !found->detected() || side->confidence > found->confidence)) found = std::move(side);
      }
  }
  eng::OrbitCamera base = front;  // the view the face is re-aimed from
  std::string turnedNote;
  bool seenFromACorner = false;
  if (!found || !found->detected()) {
    const eng::Aabb box = eng::framingBounds(drawn, eng::FramingMode::Face);
    for (const QuarterTurn& turn : box.valid() ? quarterTurns() : std::vector<QuarterTurn>()) {
      const glm::mat3 rotation = turn.rotation();
      renderer->place(glm::mat4(rotation));
      camera = turnedFraming(box, rotation);
      std::optional<Seen> turned =
          ENG_TRY_VALUE(seenNow(false));
      if (!turned || !turned->detected()) continue;
      camera = base = uprightFraming(drawn, rotation);
      std::optional<Seen> framed =
          ENG_TRY_VALUE(seenNow(false));
      found = framed && framed->detected() ? std::move(framed) : std::move(turned);
      turnedNote = "; found turned: in the file the face looks along about " + signedAxisName(turn.front) +
                   ", its top along about " + signedAxisName(turn.top) + " (glTF's front is +Z, its up +Y)";
      break;
    }
    // From the corners: the view the detector is surest of. The face is then
    // stood up level from its points (below), whatever the view's slant.
    const QuarterTurn* cornerTurn = nullptr;
    for (const QuarterTurn& turn : turnedNote.empty() && box.valid() ? quarterTurns() : std::vector<QuarterTurn>()) {
      if (!keepsTheFilesTopUp(turn)) continue;
      renderer->place(glm::mat4(turn.rotation()));
      const eng::OrbitCamera framed = turnedFraming(box, turn.rotation());
      for (const glm::vec2& corner : kCornerViews) {
        camera = framed;
        camera.yawDegrees += corner.x, camera.pitchDegrees += corner.y;
        std::optional<Seen> seen = ENG_TRY_VALUE(seenNow(false));
        if (seen && seen->detected() && (!found || !found->detected() || seen->confidence > found->confidence))
          found = std::move(seen), cornerTurn = &turn;
      }
    }
    if (cornerTurn) {
      renderer->place(glm::mat4(cornerTurn->rotation()));
      seenFromACorner = true;
    } else if (turnedNote.empty()) {
      renderer->place(glm::mat4(1.0f));
    }
  }
  if (!found && !missed.empty()) return eng::makeError(eng::ErrorKind::NotFound, missed);
  if (!found) return eng::makeError(eng::ErrorKind::NotFound, "no face found in any view of " + name + " (the front, the sides, every quarter turn)");
  // A face rolled as drawn (a scan captured with its head tilted to one
  // side), or seen from a corner, is stood up level and framed as if its
  // file held it so: its jaw line, the outline, is then found where an
  // upright face has it (rolled 45°, it lay up to 0.33 eye spans off).
  if (found->detected()) {
    const glm::vec3 side = glm::mat3(renderer->placement()) * autorig::LandmarkFrame(found->landmarks).side();
    if (seenFromACorner || std::abs(std::atan2(side.y, side.x)) > glm::radians(autorig::kLevelRollSlackDegrees)) {
      const glm::mat3 level = levelRotation(found->landmarks);
      const glm::mat4 placedBefore = renderer->placement();
      const eng::OrbitCamera cameraBefore = camera;
      renderer->place(glm::mat4(level));
      camera = uprightFraming(drawn, level);
      std::optional<Seen> levelled =
          ENG_TRY_VALUE(seenNow(false));
      if (levelled && levelled->detected()) {
        found = std::move(levelled);
        base = camera;
      } else {
        renderer->place(placedBefore), camera = cameraBefore;
      }
    }
  }
  if (seenFromACorner) {
    const autorig::LandmarkFrame frame(found->landmarks);
    turnedNote = "; found turned between the axes: in the file the face looks along " + directionName(frame.forward()) +
                 ", its top along " + directionName(frame.up()) + " (glTF's front is +Z, its up +Y)";
  }
  found->landmarks.source += turnedNote;
  const std::optional<eng::OrbitCamera> facing =
      found->detected() ? facingTheFace(base, found->landmarks, renderer->placement()) : std::optional<eng::OrbitCamera>();
  if (facing) {
    camera = *facing;
    // Should the turned view lose the face or a point, the points seen before stand.
    auto again = seenNow(false);
    if (again && *again && (*again)->detected()) {
      (*again)->landmarks.source += turnedNote;
      return std::move((*again)->landmarks);
    }
  }
  return std::move(found->landmarks);
}

}  // namespace app
