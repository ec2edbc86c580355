// Detections with depth, fused anew once the room is aligned: every view's
// region gives the thing it shows (view_segment.hpp), frame by frame into the
// instance map (instance_map.hpp), and each instance becomes one track whose
// points are the fused ones (ObjectTrack::fused). The tracks the frame pass
// made before the floor was known are only where the views come from
// (docs/ingest.md, "Objects from detections").
#pragma once

#include <optional>
#include <vector>

#include "ingest/capture/observations.hpp"
#include "ingest/geometry/alignment.hpp"
#include "ingest/geometry/instance_map.hpp"
#include "ingest/geometry/view_segment.hpp"
#include "ingest/geometry/walls.hpp"
#include "ingest/pipeline/stage_runner.hpp"
#include "model/seating.hpp"

namespace smql::ingest {

// What a fused instance needs to become a thing.
struct FusionOptions {
    double squareSlack = 1.35;       // the same for kinds that stand square to the walls (typical_sizes.hpp:
                                     // standsSquare): the apartment's fridge, turned 18 degrees at 1.37 x 0.75 m
    double wallSlack = 1.15;         // a box square to the walls when its footprint is at most this many times the
                                     // smallest one's: the orientation is then ill-determined (wallAlignedBox)
    double minHeight = 0.04;         // m: flatter instances are slivers of a surface (a table top seen as a "chair"),
                                     // unless their kind is made flatter (typical_sizes.hpp: thinnestSide)
    double minLargest = 0.06;        // m: smaller instances are specks
    double minViewShare = 0.1;       // of the frames whose view holds an instance, this share must have seen it ...
    int viewsEnough = 3;             // ... up to this many views (a detector's one-off guess is no thing);
    int oneViewOf = 4;               // and a thing seen in one frame, its pieces joined, where this many or more held
                                     // it in view is one too (with voteLabels: a closed-set detector's)
    double groundReach = 0.5;        // m: a thing that stands on floors, its bottom up to this high with nothing
                                     // under it, reaches down to the floor (its legs were hidden) ...
    double topReach = 1.3;           // ... and so does one whose top is no higher than this share of its kind's
                                     // usual top (a table whose top alone was seen)
    double restingGap = 0.1;         // m: ... unless another thing's top is this close under it
    double storedTwiceShare = 0.25;  // two things of one name, this share of the smaller's box inside the
                                     // larger's, together still of a size that suits it, are one thing stored twice
    double oneTopSpread = 0.15;      // m: ... unless they hold things on tops seen further apart than this (a desk
                                     // and the nightstand beside it): one top read twice lies within a band and
                                     // a cell (topBand + topCell)
    double namedTwiceShare = 0.45;   // two things each with this share of its box inside the other's are one
                                     // place named twice (a side table seen as a "bed" and as a "table"); of
                                     // its footprint, for two kinds that stand on floors (their boxes reach
                                     // down to it later, so their heights do not tell yet); ...
    double glimpseInside = 0.6;      // ... and one with this share inside a larger one's, seen in at most
    double glimpseShare = 0.25;      // this share of the frames that saw the larger, is a glimpse of it ...
    double glimpseTouching = 0.5;    // ... when this share of its points lie within touchReach of the larger's
    double touchReach = 0.1;         // m
    double topSlab = 0.25;           // m: a thing this thin lying on the top of one of its name is that top
    double partDepth = 0.6;          // m: a thing no deeper than this standing upright at the end of a bed or
    double partReach = 0.3;          // sofa (its centre within this of the larger's footprint), as wide as
    double partWidth = 0.6;          // this share of that end or more, rising above its top, is its headboard
                                     // or back (typical_sizes.hpp: hasUprightEnds), whatever it was named
    double seatShare = 0.6;          // a seat lower than this share of its kind's usual height (a chair's 0.54 m)
                                     // is its seat seen without its back: the upright end at one of its ends
                                     // (named as the seat or not, but no seat as low) is its back
    double roomReach = 1.0;          // m: things this close, no wall between them, stand in one room (outOfPlace)
    double lowTableSide = 0.5;       // m: luggage whose footprint sides are all this long or more, ...
    double lowTableTopMin = 0.35;    // m: its top between these heights above the floor, ...
    double lowTableTopMax = 0.6;     //
    double seatReach = 0.6;          // m: ... with places for two to sit this close, is a low table
    double smallOnTop = 0.5;         // a thing of a kind that stands on floors, resting on a top and lower than this
                                     // share of its kind's usual height, is no such thing (carrierUnder)
    double seatAtTop = 0.05;         // m: a table whose top is this close to the top of a seat ...
    double seatInside = 0.8;         // ... this share of whose footprint lies in its own is that seat (seatAtTop),
    double stoolSide = 0.45;         // m: as is a seat no longer than this (a stool) ...
    double stoolBeside = 0.3;        // ... standing this close beside it
    double seatWidth = model::kSeatPlaceWidth;  // m: a seat's places: its longest side over this, one at least
    double deskDepth = 0.9;                     // m: a table no deeper than this, ...
    double deskSideMin = 1.0;                   // m: its long side this long or longer, ...
    double deskTopMin = 0.65;                   // m: its top this high or higher, ...
    double againstWall = kAgainstWall;          // m: a long side this close to a wall's plane (wallAgainst), ...
    double chairAtDesk = 0.4;                   // m: and one chair this close, ...
    int deskChairsMax = 2;                      // or no more than this many, is a desk
    double nightstandSide = 0.9;  // m: a table no longer than this (a bedside table's 0.4-0.6 m and the slack
    double nightstandTop = 0.95;  // of boxes fused from views), its top no higher than this (ScanNet's boxes of
                                  // nightstands reach 0.83-0.92 m with what stands on them), ...
    double besideBed = 0.3;       // m: this close to a bed is a nightstand
    double topCell = 0.05;        // m: a thing whose top holds things (a table) shows its top: the points of
    double topBand = 0.1;         // m: one band of heights this thick, in its box's upper half, cover ...
    double topCover = 0.1;        // ... this share of its footprint's cells or more (seenTop)
    double overTop = 0.1;         // m: a box this much higher than the top it shows holds what stands on it
    double cabinetAbove = 0.1;    // m: a thing whose top lies from this above ...
    double cabinetBelow = 0.2;    // ... to this below a sink's bottom, ...
    double cabinetShare = 0.6;    // ... this share of its footprint under the sink's, is the cabinet the sink is set in
    double basinDepth = 0.35;  // m: a sink whose box reaches the floor, twice this tall or more, is this deep under its
                               // rim, the rest the cabinet it is set in (ScanNet's 390 labelled sinks: 0.26 m tall
                               // at the median, 0.33 m at the third quartile)
    double basinDip = 0.06;    // m: a sink's footprint cell whose highest point lies this far under its rim is its bowl
    double basinRim = 0.08;    // m: the bowl's cells grown by this on each side are the sink (ScanNet's labelled sinks:
                               // 0.56 x 0.46 m at the median, a bowl of about 0.40 x 0.30 m and its rim)
    double basinShare = 0.7;   // a bowl and rim over this share of the box's footprint is the box's own
    bool voteLabels = true;    // a closed-set detector (InstanceMapOptions::voteLabels)
};

// FusionOptions::wallSlack for photos' things, lifted on the dense points of the sides the photos saw: their
// outline follows the views more than the thing. TUM fr1/rpy's desk, seen from the chair, came 44 deg off the
// walls at 1.51 x 1.35 m (its depth camera's memory: 1.90 x 1.75 m, square to them), and square to them at
// 1.65 x 1.48 m, a footprint 1.2 times the smallest. With depth a thing is seen whole enough that its own
// orientation stands (1.25 there split fr1/rpy's desk in two).
inline constexpr double kPhotosWallSlack = 1.3;

// A camera of the capture in the aligned frame, to tell which frames held a thing in view.
struct FusionCamera {
    Pose pose;
    Intrinsics intrinsics;
};

// Whether the box `part` is an upright end of the box `whole` (a bed's headboard, a sofa's back): no deeper than
// FusionOptions::partDepth, at one of the whole's ends, as wide as a good share of that end, rising above its top.
bool uprightEndOf(const model::Box& part, const model::Box& whole, const FusionOptions& options = {});

// A thing as fusion judges it by its box: the box, its name, and how many frames saw it.
struct SeenBox {
    model::Box box;
    std::string category;
    std::size_t frames = 0;
    std::optional<double> top;  // m: the height of the top its points show (seenTop), for a thing that holds things
};

// Whether `small` is a piece of the larger `large` that the instance map kept apart: stored twice, one place
// named twice, a glimpse of it, or its top (object_fusion.cpp says how; docs/ingest.md, "Things"). `touching`:
// the share of the smaller's points within FusionOptions::touchReach of the larger's.
bool pieceOf(const SeenBox& small, const SeenBox& large, double touching, const FusionOptions& options = {});

// Whether `under` is the cabinet a sink (typical_sizes.hpp: Role::Basin) is set in, a vanity: its top right under
// the sink's bottom (FusionOptions::cabinetAbove, cabinetBelow) and most of its footprint under the sink's
// (cabinetShare); a kitchen counter's run under a sink lies mostly beside it. People, and ScanNet's labels, keep the
// two apart: the sink is the basin (of ScanNet's 390 labelled sinks in its training scans, 12 reach down to the
// floor; the median is 0.26 m tall, its bottom 0.71 m up, and 261 have a cabinet or counter labelled under them).
// Such a thing is named a cabinet by its use (namedByUse), and so is a cluster no model named (the objects stage);
// a sink whose own views took in its cabinet, its box reaching down to the floor, is parted from it at
// FusionOptions::basinDepth under its rim (object_fusion.cpp, partBasins).
bool cabinetOf(const model::Box& under, const model::Box& basin, const FusionOptions& options = {});

// The sink among `things` a table stands under, or null: a thing that holds things on its top (holdsThings; not a
// bed, whose headboard rises over its top) whose footprint lies mostly under a sink's (FusionOptions::cabinetShare) and
// whose top lies farther under the sink's bottom than a cabinet's does (cabinetBelow; that is the sink's cabinet:
// cabinetOf). Nothing put under a sink's bowl holds things: it is what holds the sink, a pedestal or a vanity's lower
// part, and its name is doubted. ScanNet's apartment, from every second and every third of its frames, stored its
// pedestal sink's column, seen in two frames, as a 0.31 x 0.22 x 0.28 m and a 0.48 x 0.46 x 0.38 m "table" under the
// bowl (ScanNet's label keeps the column in the sink's box, 0.90 m tall).
const SeenBox* sinkOverTable(const SeenBox& table, const std::vector<SeenBox>& things,
                             const FusionOptions& options = {});

// A seat among `things` standing in a table's box, most of its footprint (FusionOptions::seatInside) within the
// table's, or a stool (no side longer than FusionOptions::stoolSide) beside it (within stoolBeside), whose top is the
// table's top (within FusionOptions::seatAtTop) and no higher than seats of its kind stand (typicalHeight), or null:
// the table is that seat, or the row of stools it stands in, seen as one with what stands around it, and its name is
// doubted. A chair pushed under a table rises above its top or stays under it, and a stool at a table sits lower
// than its top (a bar's 1.0-1.1 m over stools of 0.75 m); bar stools in a row, which Open Images' SSD frames as a
// "desk", are as high as the top it gives them. But a table with things put on tables resting on its top
// (within FusionOptions::restingGap, half of each over it) is one, whatever seat stands in it: TUM's office photos,
// lifted on their dense points, had an office chair tucked under the desk, its back at the desk's top, with two
// bottles and a mug on the desk, and the desk was stored as an `object`.
const SeenBox* seatAtTop(const model::Box& table, const std::vector<SeenBox>& things,
                         const FusionOptions& options = {});

// The thing among `things` whose top carries `thing`, of a kind that stands on floors with a usual height
// (typicalHeight: a chair, a table, a fridge) and lower than FusionOptions::smallOnTop of it, or null: its bottom
// within FusionOptions::restingGap of the top of a thing that holds things (holdsThings: a table, a desk, a bed),
// over that top (its centre inside its footprint). Such a thing is no such kind: a toy, a picture, a box or a part
// of what stands on the top. A chair put on a table, whole, keeps its name. TUM fr1/rpy's colour frames stored a
// 0.24 x 0.08 x 0.07 m "chair" on the desk, among its papers.
const SeenBox* carrierUnder(const SeenBox& thing, const std::vector<SeenBox>& things,
                            const FusionOptions& options = {});

// The seat among `things` that `thing` rests on or sinks into, where things of its kind are never put on seats, or
// null: a kind that stands on floors (a table, a fridge; not a seat or luggage, which are stacked and left on
// seats) or a basin, set in a counter or hung on a wall. It rests on the seat when its centre is over the seat's
// footprint and its bottom lies between FusionOptions::restingGap over the seat's bottom (not standing on the floor
// beside it) and restingGap over the seat's top. Such a thing is a part of the seat or of what lies on it: ScanNet's
// lounge, its 100 colour frames lifted on their dense points, stored a 0.53 x 0.18 x 0.15 m "sink" in an
// armchair's back, 0.74 m up where the chair's box ends at 0.88 m.
const SeenBox* seatUnder(const SeenBox& thing, const std::vector<SeenBox>& things, const FusionOptions& options = {});

// A sink is its basin: where its views took in the counter or vanity top around the bowl, its box becomes the bowl
// and its rim. The bowl shows as cells of the footprint (FusionOptions::topCell) whose highest point lies
// FusionOptions::basinDip or more under the rim, the height nine in ten of the cells reach at most (the counter
// around the bowl; a backsplash or a tap rise over it); the largest run of them side by side is the bowl, and the
// box keeps its bounds grown by FusionOptions::basinRim, within its own, where that is at most basinShare of its
// footprint, and reaches from the bowl's floor (the lowest of its cells' highest points) to the rim: what the views
// took in under the bowl is the cabinet's front. Returns whether the box changed.
bool fitBasin(const std::vector<model::Vec3>& points, model::Box& box, const FusionOptions& options = {});

// A sink's cabinet holds the basin set in it, though its views or points showed less of it (its front, a door):
// its footprint grows, square to itself, to reach under the whole of the basin's, and its top up to the basin's
// bottom where it was lower (a sink fitted to its bowl, fitBasin, begins at the bowl's floor).
void reachUnder(model::Box& cabinet, const model::Box& basin);

// Things of kinds that stand on floors whose legs or base the views did not see reach down to the floor: the
// one found; or one placed that the lowest thing reaches down to, or placed a table's height under a table top
// (`tableTopHeight`, Alignment::tableTopHeight) that a table's box holds (object_fusion.cpp, standOnFloor).
// Returns how many were extended.
std::size_t reachDownToFloor(std::vector<SeenBox>& things, bool floorFound, std::optional<double> tableTopHeight = {},
                             const FusionOptions& options = {});

// Things of a kind that stands in one kind of room (typical_sizes.hpp: roomKind; a toilet) with more things of
// another room's kinds (a fridge, an oven, a microwave) than of their own, themselves counted, within
// FusionOptions::roomReach and no wall between: not of that kind (two white bins beside a fridge that a
// detector calls a toilet in every view). And things of a kind that stands in any room but a bathroom (RoomKind::Dry:
// a bed, a sofa, a desk, a chair) with a toilet that close: a bathtub its views called a bed, a chair or a desk.
// Returns, per thing, why its name is doubted, or "".
std::vector<std::string> outOfPlace(const std::vector<SeenBox>& things, const std::vector<WallSegment>& walls,
                                    const FusionOptions& options = {});

// Things named by what they are used as, where the detectors' classes have no name for them (COCO has no desk;
// COCO and Open Images have no ottoman):
// - a low table: luggage (typical_sizes.hpp: Role::Luggage; a suitcase, a box) standing on the floor, as large as a
//   low table (FusionOptions::lowTableSide, lowTableTopMin..Max), with places for two or more to sit within
//   seatReach (a seat's places: its longest side over seatWidth, one at least): an ottoman or a trunk before a sofa
//   or among chairs;
// - a nightstand: a table no longer than nightstandSide, its top no higher than nightstandTop, within besideBed of a
//   bed;
// - a cabinet: a thing (not a seat, nor another sink) right under a sink, the cabinet it is set in (cabinetOf);
// - a desk: a table no deeper than deskDepth and no shorter than deskSideMin, its top deskTopMin high or higher, a
//   long side against a wall (within againstWall of its plane, parallel to it) and one chair within chairAtDesk, or
//   up to deskChairsMax: where one or two people work. (Of ScanNet's labelled desks and tables, 1,201 rooms of its
//   training scans, 60 % of desks have one chair within 0.3 m and 19 % two; tables under 1 m long are side tables.
//   chairAtDesk is 0.1 m wider for boxes measured a few centimetres short: it names the same labelled desks.)
// Returns, per thing, the name it is used under and why ("" and "" for the others).
struct UseName {
    std::string category;
    std::string why;
};
std::vector<UseName> namedByUse(const std::vector<SeenBox>& things, const std::vector<WallSegment>& walls,
                                const FusionOptions& options = {});

// A thing's top as its points show it: the largest share of its box's footprint (cells of FusionOptions::topCell)
// that the points of one band of heights, topBand thick, above the box's lowest quarter cover, and the highest of
// those points. A table's top covers much of its footprint; the seats of bar stools an Open Images "desk" framed, or
// a window ledge seen in two frames, little. A thing whose top holds things (a table, a desk, a counter; not a bed,
// whose headboard rises over its top) covering less than topCover shows no top: its name is doubted. The band may lie
// low in the box: the views merge a desk with the monitors on it.
struct SeenTop {
    double cover = 0;   // share of the footprint's cells
    double height = 0;  // m: the band's highest point (the box's bottom when no point is in it)
};
SeenTop seenTop(const std::vector<model::Vec3>& points, const model::Box& box, const FusionOptions& options = {});

// A thing whose top holds things, with a top seen (SeenTop::cover at least topCover) and its box reaching more than
// FusionOptions::overTop above that top: the box is lowered to its top, since what rises above it stands on it (the
// views merged a desk and its monitors into one box 0.3 m taller than the desk). Returns whether it was lowered.
bool lowerToTop(model::Box& box, const SeenTop& top, const FusionOptions& options = {});

// A thing fusion made: its box and the name it is stored under; where fusion did not keep the detectors' name, that
// name (detectedAs) and why (no top, outOfPlace: "object"; namedByUse: "table", "desk"), else ""; its fused points
// (aligned frame, colours RGB) and the views it was made of (indices into ObjectFusion's views, in frame order).
struct FusedThing {
    model::Box box;
    std::string category;
    std::string detectedAs;
    std::string renamedWhy;
    PointCloud points;
    std::vector<std::size_t> views;
};

// What making the things did, for the ingest's note.
struct FusionCounts {
    std::size_t segmented = 0;  // views that showed a thing apart from the floor and walls
    std::size_t views = 0;      // views added
    std::size_t mapMerged = 0, pieces = 0, ends = 0, slivers = 0, guesses = 0, lowered = 0, grounded = 0, basins = 0,
                bowls = 0;
};

// Object fusion frame by frame: each frame's views go into the instance map as the frame comes (addFrame), and
// the things are made from the map whenever they are asked for (things), so the objects of a capture can be read
// while its frames stream in, and a recorded capture's once its last frame is in (fuseTracks).
class ObjectFusion {
public:
    ObjectFusion(const Alignment& alignment, const RoomSurfaces& room, FusionOptions options = {});
    // Not copied or moved: its room's surfaces point at its own walls.
    ObjectFusion(const ObjectFusion&) = delete;
    ObjectFusion& operator=(const ObjectFusion&) = delete;
    // A camera whose frame the detectors looked at: what "held in view but not seen" is counted over.
    void addCamera(const FusionCamera& camera);
    // One frame's views of things (all of that frame's, in the capture's frame), frames in the order taken.
    void addFrame(std::vector<Observation> frameViews);
    // The points of a view that lie on its thing (empty when too few): a view's alone, so views can be cut apart
    // on several threads before their frames are added in order (addSegmentedFrame).
    PointCloud segment(const Observation& view) const;
    // addFrame with each view's points already cut by segment(), one cloud a view.
    void addSegmentedFrame(std::vector<Observation> frameViews, std::vector<PointCloud> things);
    // The things the frames so far show: instances merged, pieces joined, tables lowered to their tops, grounded,
    // slivers dropped, names doubted where they show no top or stand out of place, low tables and desks named by
    // their use. The map itself is left to take more frames.
    std::vector<FusedThing> things(FusionCounts* counts = nullptr) const;
    const std::vector<Observation>& views() const { return views_; }
    std::vector<Observation> takeViews() { return std::move(views_); }

private:
    Alignment alignment_;
    std::vector<WallSegment> walls_;  // the fusion's own copy: the caller's may be gone by the next frame
    RoomSurfaces room_;               // with walls_ as its walls
    FusionOptions options_;
    InstanceMap map_;
    std::vector<FusionCamera> cameras_;
    std::vector<Observation> views_;
    std::size_t segmented_ = 0;
};

std::vector<ObjectTrack> fuseTracks(std::vector<ObjectTrack> tracks, const Alignment& alignment,
                                    const RoomSurfaces& room, const std::vector<FusionCamera>& cameras,
                                    const FusionOptions& options, StageProgress& progress);

}  // namespace smql::ingest
