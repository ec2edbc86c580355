#include "ingest/pipeline/plausibility.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "ingest/geometry/scale_priors.hpp"
#include "ingest/geometry/typical_sizes.hpp"
#include "ingest/geometry/walls.hpp"
#include "model/category.hpp"
#include "model/geometry.hpp"
#include "relations/predicates.hpp"

namespace smql::ingest {

using relations::Support;
using relations::usualSupport;

namespace {

// Where people and robots hold cameras (m above the floor): warned outside the first range,
// refused outside the second.
constexpr double kCameraWarn[2] = {0.3, 2.3};
constexpr double kCameraRefuse[2] = {0.12, 3.2};
constexpr double kUsualCamera = 1.4;  // a phone held by a standing person
// Photos without depth whose scale the ingest estimated: their cameras' height is one of the scale's priors, a
// person's assumed, and the things' heights lead it where two agree. Cameras those put higher than a person holds
// one say the scale is too large, the things that led it short of their kinds together, and the memory is refused. Real
// captures' cameras stand 1.19-1.70 m up (ScanNet's 1.19-1.36, 7-Scenes' 1.41, TUM's 1.50-1.70); TUM's office
// photos, the last 8 of 17, were stored 1.245x too large with their cameras 1.94 m up, two chairs and a "fridge"
// leading the scale 22 % from the cameras' height, and ScanNet's bathroom once 1.36x with its cameras 1.82 m up.
constexpr double kPhotosCameraTop = 1.8;
// Rooms' ceilings (m).
constexpr double kCeilingWarn[2] = {2.0, 5.0};
constexpr double kCeilingRefuse[2] = {1.4, 9.0};
// The median thing against its kind's largest side: about 0.6 in real rooms (most things are not
// the largest of their kind).
constexpr double kRatioWarn[2] = {0.25, 1.7};
constexpr double kRatioRefuse[2] = {0.12, 3.0};
constexpr double kUsualRatio = 0.6;
constexpr std::size_t kMinNamedThings = 3;
// When the cameras' height and the things' sizes both say the scale is off, the same way, their
// geometric mean is the scale's error: refused past these factors. Each alone varies more (a robot's
// low camera, a room of small things); together they are a wrong depth unit or --scale.
constexpr double kAgreedRefuse[2] = {0.55, 1.8};
// The share of points two frames see at the same depth: real captures with right poses 0.93 to
// 0.99; mirrored images 0.58, depth in a unit 1.4x off 0.72 (docs/ingest.md, "Plausibility").
constexpr double kAgreementWarn = 0.85;
constexpr double kAgreementRefuse = 0.7;
// Photos without depth take their scale from priors (the cameras' height above the floor, the heights of things
// standing on it, the ceiling's): further apart than this ((largest - smallest) / the scale), they were measured
// from a wrong floor or by a camera far from a person's height, and the memory is refused. Right memories' priors
// measured 1-17 % apart; wrong ones 28 % (a ScanNet bathroom's photos stored 1.36x too large), 31 % and 39 % (TUM's
// desk, its top taken for the floor: 2.4x and 1.8x) (docs/ingest.md, "Photos without depth against the truth").
// Two priors a factor apart (scale_priors.hpp: kDisagreement) are further apart still: refused as well, the
// factor named.
constexpr double kSpreadRefuse = 0.25;
// Degrees between the photos' vertical edges and a floor seen well beyond which the reconstruction is bent.
// Real captures with their camera right: 0.4-1.6 (the dining photos, ScanNet's lounge and bathroom); 7-Scenes'
// red kitchen's colour photos given its depth camera's 585 px for their 526: 5.3.
constexpr double kBentEdges = 4;
// The object checks (objectFindings), metres but where said. A sliver: its thinnest side under the side no thing of
// its kind is thinner than (typical_sizes.hpp: thinnestSide, which object fusion drops at ingest).
// Floating: a thing that stands on floors with its bottom this high, nothing under it within kRests.
constexpr double kFloating = 0.3;
constexpr double kRests = 0.1;
// Behind a wall: its centre this far beyond the wall's plane, within the wall's extent.
constexpr double kBehindWall = 0.15;
// A duplicate: this share of the smaller box inside the larger, same category.
constexpr double kDuplicateShare = 0.5;
// In pieces: two of a kind this close, together no larger than the largest of their kind, each
// under this share of it.
constexpr double kPiecesGap = 0.05;
constexpr double kPieceShare = 0.6;
// The camera's height says the scale is right when within this factor of a person's (kUsualCamera):
// the sizes of named things then speak of wrong boxes, not of a wrong depth unit.
constexpr double kCameraAgrees = 1.35;

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : (v[v.size() / 2 - 1] + v[v.size() / 2]) / 2;
}

double largestSide(const model::Box& box) { return std::max({box.size.x, box.size.y, box.size.z}); }

// The name a thing's size is judged by: a detector's name kept only as `detected_as` for a box far
// too large for it still counts, since a wrong scale makes every box too large for its name.
const std::string& sizedName(const model::Node& node) {
    for (const auto& a : node.attributes)
        if (a.name == "detected_as") return a.value;
    return node.category;
}

// The fix for a scale off by `factor` (measured / usual): the depth unit, --scale, or the floor.
std::string scaleFix(double factor, const ScaleSource& source) {
    if (source.stored)
        return fmt::format(
            "sizes suggest the scale is {:.2g}x too {}: ingest the capture again with --depth-scale (depth in another "
            "unit) or --scale",
            factor >= 1 ? factor : 1 / factor, factor >= 1 ? "large" : "small");
    if (source.depth)
        return fmt::format(
            "the depth images may be in another unit: give --depth-scale (depth units per metre: 1000 for "
            "millimetres, 5000 for TUM); its measures suggest about --depth-scale {:.0f}",
            source.depthScale * factor);
    if (source.metric)
        return fmt::format(
            "the capture's poses may not be in metres: give --scale (metres per pose unit); its "
            "measures suggest about --scale {:.3g}",
            1 / factor);
    if (source.given)
        return fmt::format("--scale may be wrong: the capture's measures suggest about {:.3g} times it", 1 / factor);
    return fmt::format(
        "the scale was estimated from the capture: give --scale (metres per capture unit), a camera.json with "
        "depth, or more views of the floor and of things of known size; sizes suggest the scale is {:.2g}x too {}",
        factor >= 1 ? factor : 1 / factor, factor >= 1 ? "large" : "small");
}

void judge(PlausibilityReport& report, const char* check, double value, const double warn[2], const double refuse[2],
           const std::string& what, const std::string& fix) {
    if (value >= warn[0] && value <= warn[1]) return;
    const bool out = value < refuse[0] || value > refuse[1];
    report.findings.push_back({check, out, what, fix});
}

}  // namespace

bool PlausibilityReport::refused() const {
    return std::any_of(findings.begin(), findings.end(), [](const auto& f) { return f.refuse; });
}

PlausibilityReport checkPlausibility(const model::SceneData& scene, const ScaleSource& source,
                                     std::vector<double> cameraHeights) {
    PlausibilityReport report;
    bool floor = false;
    std::vector<double> frames, ratios;
    for (const auto& n : scene.nodes) {
        if (n.kind == model::NodeKind::Anchor && n.category == "floor") floor = true;
        if (n.kind == model::NodeKind::Anchor && n.category == "ceiling") report.ceilingHeight = n.box.center.z;
        if (n.kind == model::NodeKind::Frame) frames.push_back(n.box.center.z);
        if (n.kind != model::NodeKind::Object || n.geometry == model::GeometryKind::None) continue;
        if (auto usual = typicalExtent(sizedName(n))) ratios.push_back(largestSide(n.box) / *usual);
    }
    // The ingest says why the floor was not seen (alignmentFindings); a stored memory only shows that
    // it has none, which leaves its heights and its scale unchecked.
    if (source.stored && !floor && !frames.empty())
        report.findings.push_back({"floor", false, "the memory holds no floor: its capture did not show one",
                                   "the cameras' height and the scale could not be checked against it; ingest the "
                                   "capture again with views of the floor, or with --scale"});
    std::vector<double>& cameras = !cameraHeights.empty() ? cameraHeights : frames;
    if (cameras.empty() && scene.info.viewpoint.position != model::Vec3{}) cameras = {scene.info.viewpoint.position.z};
    // A height given (--camera-height) set the scale: the cameras stand at it, and judging them would judge the
    // user's measurement; it is what the other checks expect of them, a robot's low camera included.
    const double usualCamera = source.cameraHeight.value_or(kUsualCamera);
    if (floor && !cameras.empty()) {
        report.cameraHeight = median(cameras);
        const bool estimated = !source.stored && !source.scaled();
        const double photosWarn[2] = {kCameraWarn[0], kPhotosCameraTop};
        const double photosRefuse[2] = {kCameraRefuse[0], kPhotosCameraTop};
        if (!source.cameraHeight)
            judge(report, "camera height", *report.cameraHeight, estimated ? photosWarn : kCameraWarn,
                  estimated ? photosRefuse : kCameraRefuse,
                  estimated && *report.cameraHeight > kPhotosCameraTop
                      ? fmt::format("the cameras are {:.2f} m above the floor, where a person holds one at most {:g} "
                                    "m up (real captures' stand 1.19-1.70 m)",
                                    *report.cameraHeight, kPhotosCameraTop)
                      : fmt::format("the cameras are {:.2f} m above the floor (people and robots hold them {:g} to "
                                    "{:g} m up)",
                                    *report.cameraHeight, kCameraWarn[0], kCameraWarn[1]),
                  *report.cameraHeight > 0 ? scaleFix(*report.cameraHeight / usualCamera, source)
                                           : std::string("the floor found is above the cameras: check the capture"));
    }
    if (report.ceilingHeight)
        judge(report, "ceiling height", *report.ceilingHeight, kCeilingWarn, kCeilingRefuse,
              fmt::format("the ceiling is {:.2f} m above the floor (rooms: {:g} to {:g} m)", *report.ceilingHeight,
                          kCeilingWarn[0], kCeilingWarn[1]),
              scaleFix(*report.ceilingHeight / 2.6, source));
    report.namedThings = ratios.size();
    if (ratios.size() >= kMinNamedThings) {
        report.sizeRatio = median(ratios);
        // Cameras at a person's height say the scale is right: sizes far off are the boxes' fault.
        const bool camerasAgree = report.cameraHeight && *report.cameraHeight >= usualCamera / kCameraAgrees &&
                                  *report.cameraHeight <= usualCamera * kCameraAgrees;
        judge(report, "sizes of named things", *report.sizeRatio, kRatioWarn, kRatioRefuse,
              fmt::format("the named things are {:.2f} times the largest of their kinds, at the median of {} "
                          "(real rooms: about {:g})",
                          *report.sizeRatio, ratios.size(), kUsualRatio),
              camerasAgree ? fmt::format("the cameras' height ({:.2f} m) says the scale is right: the things' boxes "
                                         "are wrong, not the depth unit (see the objects flagged below)",
                                         *report.cameraHeight)
                           : scaleFix(*report.sizeRatio / kUsualRatio, source));
        // A refusal needs the scale to be wrong; the cameras say it is not.
        if (camerasAgree && !report.findings.empty() && report.findings.back().check == "sizes of named things")
            report.findings.back().refuse = false;
    }
    report.objects = objectFindings(scene);
    if (!report.objects.empty())
        report.findings.push_back(
            {"objects", false,
             fmt::format("{} of the things do not look like what they are named (listed below)", report.objects.size()),
             "check them with DESCRIBE and their evidence crops; slivers, pieces and duplicates come from "
             "detections of parts of things"});
    if (report.cameraHeight && report.sizeRatio && *report.cameraHeight > 0) {
        const double byCameras = *report.cameraHeight / usualCamera, bySizes = *report.sizeRatio / kUsualRatio;
        const bool agree = (byCameras < 1) == (bySizes < 1);
        const double factor = std::sqrt(byCameras * bySizes);
        if (agree && (factor < kAgreedRefuse[0] || factor > kAgreedRefuse[1]))
            report.findings.push_back(
                {"scale", true,
                 fmt::format("the cameras' height ({:.2f} m) and the named things' sizes ({:.2f} of their kinds' "
                             "largest) both say the scale is about {:.2g}x too {}",
                             *report.cameraHeight, *report.sizeRatio, factor >= 1 ? factor : 1 / factor,
                             factor >= 1 ? "large" : "small"),
                 scaleFix(factor, source)});
    }
    return report;
}

std::optional<PlausibilityFinding> viewAgreementFinding(const ViewAgreement& agreement) {
    if (!agreement.tested() || agreement.share() >= kAgreementWarn) return std::nullopt;
    return PlausibilityFinding{
        "views", agreement.share() < kAgreementRefuse,
        fmt::format("the frames' depth images disagree through their poses: of {} points seen from two frames, "
                    "{:.0f}% are at the depth the other frame reads, {:.0f}% are seen through (captures with right "
                    "poses: over {:.0f}% agree)",
                    agreement.agree + agreement.conflict, 100 * agreement.share(), 100 * (1 - agreement.share()),
                    100 * kAgreementWarn),
        "check that the poses are camera-to-world with the camera looking along +z, x right and y down (a "
        "mirrored image or a focal length's sign turned over mirrors every view), and the depth unit "
        "(--depth-scale: depth units per metre)"};
}

namespace {

// A scale on the cameras' assumed height alone, and why nothing checked it: no second prior, or things standing on
// the floor whose heights were set aside for disagreeing (Alignment::scaleThingsApart), or left out of the heights
// prior (scaleThingsLeftOut: beside another room's things, reaching below the floor, seen in part), the rest too few.
std::string restsOnCamerasHeight(const Alignment& alignment) {
    const HeightsLeftOut& left = alignment.scaleThingsLeftOut;
    std::vector<std::string> why;
    if (!alignment.scaleThingsApart.empty())
        why.push_back(fmt::format(
            "the heights of {} standing on the floor do not check them: no two of them give a scale within {:.0f}% "
            "of each other's",
            alignment.scaleThingsApart, 100 * kThingsAgree));
    if (!left.doubted.empty())
        why.push_back(fmt::format(
            "the heights of {} standing on the floor do not check them: each stands by things of another kind "
            "of room (a kitchen's by a bathroom's), and one of the two names is wrong",
            left.doubted));
    if (!left.belowFloor.empty())
        why.push_back(fmt::format(
            "the heights of {} do not check them: their points reach well below the floor found, so either that "
            "floor is not the one they stand on or their points take in more than the things",
            left.belowFloor));
    if (!left.partial.empty())
        why.push_back(fmt::format(
            "the heights of {} do not check them: seen in part, short of the tallest of their kind", left.partial));
    if (!left.counted.empty())
        why.push_back(
            fmt::format("{}, {}, is too few: the things' heights make a prior from two things on",
                        why.empty() ? "the one thing of a known height standing on the floor" : "what is left of them",
                        left.counted));
    const std::string unchecked =
        why.empty()
            ? std::string("no second prior (things of a known height standing on the floor, the ceiling) checks them")
            : fmt::format("{}", fmt::join(why, "; "));
    return "the scale rests on one prior, the cameras' assumed height above the floor, where real captures' cameras "
           "stand 1.2-1.7 m up: lengths may be a fifth off, and " +
           unchecked;
}

}  // namespace

std::optional<PlausibilityFinding> thinPointsFinding(const PointsGiven& given) {
    if (given.cover >= kCoverToStore) return std::nullopt;
    return PlausibilityFinding{
        "points", !given.scaled,
        fmt::format("the photos give few points to measure the room on: COLMAP's {} and {} dense ones from {} photo{} "
                    "cover {:.0f}% of what the detectors saw (those of rooms stored right cover more than half), so "
                    "the floor and the things standing on it were placed on too few points to be told",
                    given.sparse, given.dense, given.photos, given.photos == 1 ? "" : "s", 100 * given.cover),
        std::string("photos that are dark, blurred, plain or far apart match in few places: take more, each a short "
                    "step from the one before, in more light") +
            (given.scaled || given.scaleOffered ? "" : ", or give --scale (metres per capture unit)")};
}

std::vector<PlausibilityFinding> alignmentFindings(const Alignment& alignment, const ScaleSource& source) {
    std::vector<PlausibilityFinding> out;
    const bool scaled = source.scaled();
    // Photos without depth whose floor was placed under a table top by the cameras' assumed height and a table's,
    // where the heights of things standing on the top measure it too (scale_priors.hpp: scaleFromHeightsOnTop):
    // the priors' spread, refused below when wide, says whether the placement holds.
    const bool placedOnTop = !scaled && alignment.tableTopHeight && alignment.scalePriors >= 2;
    // Under a table top the floor may truly be out of view; where the points hold no level surface at all, the photos
    // may well show the floor (the five dining photos' carpet) without their points measuring it.
    if (!alignment.floorNotSeen.empty())
        out.push_back({"floor", !scaled && !placedOnTop,
                       (alignment.tableTopHeight ? "the floor is not seen: " : "the floor is not measured: ") +
                           alignment.floorNotSeen,
                       scaled ? fmt::format("the floor is placed {}; views that also show the floor place it where "
                                            "it is",
                                            alignment.floorPlaced)
                       : placedOnTop
                           ? fmt::format("the floor is placed {}, which the cameras' assumed height and the things on "
                                         "the top agree on within {:.0f}%; photos that also show the floor place it "
                                         "where it is",
                                         alignment.floorPlaced, 100 * alignment.scaleSpread)
                           : std::string("photos without depth take their scale from the floor: give --scale "
                                         "(metres per capture unit), or add photos that show the floor")});
    if (!alignment.floorUnconfirmed.empty() && !scaled)
        out.push_back({"floor", true, "the floor is not confirmed: " + alignment.floorUnconfirmed,
                       "photos without depth take their scale from the floor: give --scale (metres per capture "
                       "unit), or add photos that show the floor and the chairs, tables or beds standing on it"});
    if (alignment.edgesFromFloor && *alignment.edgesFromFloor > kBentEdges)
        out.push_back(
            {"vertical edges", false,
             fmt::format("the photos' vertical edges stand {:.1f} deg from the floor's normal, where a room's "
                         "walls and legs stand upright on it: the reconstruction is bent, so heights and "
                         "sizes lean; a focal length off (a camera.json of another camera, such as a depth "
                         "camera's) or a lens's distortion does this",
                         *alignment.edgesFromFloor),
             "give the photos' own camera (camera.json, --camera), or none for COLMAP to estimate it"});
    const std::string priorsFix =
        source.cameraHeight
            ? "the cameras' height given leads: the floor found may be a table top, or the things are misnamed; add "
              "photos that show the floor and the things standing on it"
            : "give --camera-height (the cameras' height above the floor in metres, when known) or --scale (metres "
              "per capture unit), or add photos that show the floor and the things standing on it";
    if (alignment.scaleSplit > 0)
        out.push_back({"scale priors", true,
                       fmt::format("the scale's two priors disagree by a factor of {:.2g} (the cameras' height above "
                                   "the floor and the heights of things standing on it): the floor found may be a "
                                   "table top, or the cameras are far from a person's height",
                                   alignment.scaleSplit),
                       priorsFix});
    else if (alignment.scaleSpread > kSpreadRefuse)
        out.push_back({"scale priors", true,
                       fmt::format("the scale's priors are {:.0f}% apart (the cameras' height above the floor, the "
                                   "heights of things standing on it, the ceiling's): the floor found may be a table "
                                   "top, and lengths may be off by as much",
                                   100 * alignment.scaleSpread),
                       priorsFix});
    // Photos without depth whose scale rests on one prior: in practice the cameras' assumed height, since the
    // things' heights and the ceiling come only with a floor under the cameras. Real captures' cameras stand
    // 1.19-1.70 m up (ScanNet's 1.19-1.36, 7-Scenes' 1.41, TUM's 1.50-1.70), so that prior alone leaves
    // lengths a fifth off: a fresh COLMAP run of ScanNet's lounge was stored on it 1.19x too large. Two photos
    // a short step apart whose dense points are one pair's alone are looser still: COLMAP stored two of the
    // lounge's frames 5 cm apart 3.6 times as far apart for their depth as they were, and the cameras' height
    // then put the room 4.4x too large (docs/ingest.md, "One pair alone"). A second prior checks the room's
    // proportions.
    // (A floor not seen or not confirmed is refused above, and says why.)
    // The cameras' height given (--camera-height) is a measurement, not that assumption; one pair's depth is loose
    // across the room whatever its scale.
    else if (!scaled && alignment.scalePriors < 2 &&
             (source.onePairDepth ||
              (!source.cameraHeight && alignment.floorNotSeen.empty() && alignment.floorUnconfirmed.empty())))
        out.push_back(
            {"scale priors", true,
             source.onePairDepth
                 ? std::string("the dense points are one pair of photos' alone, drawn from two poses that nothing "
                               "else checks (a short step between them leaves their depth loose), and the scale "
                               "rests on one prior: nothing checks the room's proportions")
                 : restsOnCamerasHeight(alignment),
             source.onePairDepth ? "give --scale (metres per capture unit), or add photos of the room, whose pairs "
                                   "check each other's depth"
                                 : priorsFix});
    return out;
}

namespace {

std::string named(const model::Node& n) { return fmt::format("{}#{}", n.category, n.id); }
std::string measures(const model::Box& b) {
    return fmt::format("{:.2f} x {:.2f} x {:.2f} m", b.size.x, b.size.y, b.size.z);
}

// The share of a's volume inside b (axis-aligned bounds of the upright boxes).
double insideShare(const model::Box& a, const model::Box& b) {
    const auto ba = model::worldAabb(a), bb = model::worldAabb(b);
    const double x = std::max(0.0, std::min(ba.max.x, bb.max.x) - std::max(ba.min.x, bb.min.x));
    const double y = std::max(0.0, std::min(ba.max.y, bb.max.y) - std::max(ba.min.y, bb.min.y));
    const double z = std::max(0.0, std::min(ba.max.z, bb.max.z) - std::max(ba.min.z, bb.min.z));
    const double volume = (ba.max.x - ba.min.x) * (ba.max.y - ba.min.y) * (ba.max.z - ba.min.z);
    return volume > 0 ? x * y * z / volume : 0;
}

// What `n` rests on: a box whose top is within kRests of its bottom under its footprint's centre.
const model::Node* restingOn(const model::Node& n, const std::vector<const model::Node*>& things) {
    const double bottom = n.box.center.z - n.box.size.z / 2;
    for (const auto* other : things) {
        if (other == &n) continue;
        const auto b = model::worldAabb(other->box);
        if (n.box.center.x >= b.min.x && n.box.center.x <= b.max.x && n.box.center.y >= b.min.y &&
            n.box.center.y <= b.max.y && std::abs(b.max.z - bottom) <= kRests)
            return other;
    }
    return nullptr;
}

}  // namespace

std::string objectWarning(const ObjectFinding& finding) {
    return fmt::format("warning: {}: {}", finding.problem, finding.what);
}

bool storedTwice(const model::Box& smaller, const model::Box& larger) {
    return insideShare(smaller, larger) >= kDuplicateShare;
}

namespace {

// A cabinet beside a wall with nothing under it hangs on the wall: the objects stage names a thing no model named that
// hangs so a cabinet (objects_from_clusters.hpp: hungOnWall, by the same gap to the wall's box), a wall cabinet, which
// is held up, not floating.
bool cabinetOnWall(const model::Node& n, const std::vector<const model::Node*>& walls) {
    return n.category == "cabinet" && std::any_of(walls.begin(), walls.end(), [&](const model::Node* wall) {
               return model::horizontalGap(n.box, wall->box) <= kAgainstWall;
           });
}

}  // namespace

bool floatsOverNothing(const model::Node& n, const std::vector<const model::Node*>& things) {
    // By the stored name: a thing stored as 'object' (its detector's name kept as a guess) claims no support.
    return usualSupport(n.category) == Support::Floor && model::bottom(n.box) > kFloating && !restingOn(n, things);
}

std::vector<ObjectFinding> objectFindings(const model::SceneData& scene) {
    std::vector<const model::Node*> things, walls;
    std::vector<model::Vec3> cameras;
    bool floor = false;
    for (const auto& n : scene.nodes) {
        if (n.geometry == model::GeometryKind::None) continue;
        if (n.kind == model::NodeKind::Object) things.push_back(&n);
        if (n.kind == model::NodeKind::Anchor && n.category == "wall") walls.push_back(&n);
        if (n.kind == model::NodeKind::Anchor && n.category == "floor") floor = true;
        if (n.kind == model::NodeKind::Frame) cameras.push_back(n.box.center);
    }
    std::vector<ObjectFinding> out;
    std::vector<bool> flagged(things.size(), false);
    auto flag = [&](std::size_t i, const char* problem, std::string what) {
        if (flagged[i]) return;
        flagged[i] = true;
        out.push_back({things[i]->id, problem, std::move(what)});
    };
    for (std::size_t i = 0; i < things.size(); ++i) {
        const model::Node& n = *things[i];
        const auto made = thinnestSide(sizedName(n));
        const double thinnest = std::min({n.box.size.x, n.box.size.y, n.box.size.z});
        if (made && thinnest < *made) {
            const model::Node* under = restingOn(n, things);
            flag(
                i, "sliver",
                fmt::format("{} ({}) is {:.2g} cm thin, no {} is{}", named(n), measures(n.box), 100 * thinnest,
                            sizedName(n), under ? fmt::format(": a piece of {}'s top it lies on", named(*under)) : ""));
        }
        if (floor && floatsOverNothing(n, things) && !cabinetOnWall(n, walls))
            flag(i, "floating",
                 fmt::format("{} ({}) stands on floors, but its bottom is {:.2f} m up with nothing under it", named(n),
                             measures(n.box), model::bottom(n.box)));
    }
    // Behind a wall: the side of its plane away from the cameras (or from the things' middle).
    model::Vec3 inside{0, 0, 0};
    const auto& around = cameras.empty() ? std::vector<model::Vec3>{} : cameras;
    for (const auto& c : around) inside = {inside.x + c.x / around.size(), inside.y + c.y / around.size(), 0};
    if (around.empty())
        for (const auto* t : things)
            inside = {inside.x + t->box.center.x / things.size(), inside.y + t->box.center.y / things.size(), 0};
    for (const auto* wall : walls) {
        // In the wall's frame, x runs along it and y across it.
        const model::BoxFrame frame(wall->box);
        const double roomSide = frame.local({inside.x, inside.y}).y >= 0 ? 1 : -1;
        for (std::size_t i = 0; i < things.size(); ++i) {
            const model::Vec2 at = frame.local({things[i]->box.center.x, things[i]->box.center.y});
            if (std::abs(at.x) <= wall->box.size.x / 2 && roomSide * at.y < -(wall->box.size.y / 2 + kBehindWall))
                flag(i, "behind a wall",
                     fmt::format("{} stands {:.2f} m behind {}: seen through it, or in a mirror", named(*things[i]),
                                 -roomSide * at.y - wall->box.size.y / 2, named(*wall)));
        }
    }
    // Two of a kind: one inside the other (a duplicate), or touching and together the size of one.
    for (std::size_t i = 0; i < things.size(); ++i)
        for (std::size_t j = 0; j < things.size(); ++j) {
            if (i == j || things[i]->category != things[j]->category || things[i]->category == model::kUnnamedCategory)
                continue;
            const model::Node& a = *things[i];
            const model::Node& b = *things[j];
            const bool smaller =
                model::volume(a.box) < model::volume(b.box) || (model::volume(a.box) == model::volume(b.box) && i > j);
            if (!smaller) continue;
            if (storedTwice(a.box, b.box)) {
                flag(i, "duplicate",
                     fmt::format("{} lies mostly inside {}: one {} stored twice", named(a), named(b), a.category));
                continue;
            }
            const auto usual = typicalExtent(a.category);
            if (!usual || model::distance(a.box, b.box) > kPiecesGap) continue;
            const auto ua = model::worldAabb(a.box), ub = model::worldAabb(b.box);
            const double together = std::max({std::max(ua.max.x, ub.max.x) - std::min(ua.min.x, ub.min.x),
                                              std::max(ua.max.y, ub.max.y) - std::min(ua.min.y, ub.min.y),
                                              std::max(ua.max.z, ub.max.z) - std::min(ua.min.z, ub.min.z)});
            if (together <= *usual && largestSide(a.box) < kPieceShare * *usual &&
                largestSide(b.box) < kPieceShare * *usual)
                flag(i, "in pieces",
                     fmt::format("{} and {} touch and together measure {:.2f} m: one {} in pieces?", named(a), named(b),
                                 together, a.category));
        }
    return out;
}

NameFit nameFit(const std::string& category, const model::Box& box, BoxMeasure measure) {
    const double beyond = measure == BoxMeasure::Depth ? kBeyondTypicalExtent : kBeyondTypicalHull;
    if (auto usual = typicalExtent(category); usual && largestSide(box) > beyond * *usual) return NameFit::TooLarge;
    if (auto deepest = deepestFootprint(category);
        deepest && measure == BoxMeasure::Depth && std::min(box.size.x, box.size.y) > *deepest)
        return NameFit::TooDeep;
    if (smallerThanKind(category, largestSide(box), box.size.z, box.center.z - box.size.z / 2))
        return NameFit::TooSmall;
    if (slenderForKind(category, std::max(box.size.x, box.size.y), std::min(box.size.x, box.size.y), box.size.z))
        return NameFit::TooSlender;
    if (auto lowest = lowestTop(category); lowest && measure == BoxMeasure::Depth && model::top(box) < *lowest)
        return NameFit::TooLow;
    if (auto height = typicalHeight(category); measure == BoxMeasure::HullHeldToSurface && height &&
                                               !hasUprightEnds(category) &&
                                               box.size.z > kTallerThanTypicalHull * *height)
        return NameFit::TooTall;
    // A hull from boxes alone bounds its height without measuring it; one held to its surfaces reaches past them as
    // it does past a standard height.
    if (auto tallest = tallestHeight(category);
        tallest && measure != BoxMeasure::HullFromBoxes &&
        box.size.z > (measure == BoxMeasure::Depth ? 1.0 : kTallerThanTypicalHull) * *tallest)
        return NameFit::TooTall;
    return NameFit::Fits;
}

}  // namespace smql::ingest
