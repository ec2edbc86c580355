// A person's measures, one rule for the whole engine: how many people a seat takes (ingest's low tables among
// seats, object_fusion.cpp seatsAround, and ASK's "how many people can sit here?" count places by it), and the
// room a walking person keeps (GUIDE's free floor, and ASK's "is there room to walk between the bed and the wall?").
#pragma once

#include <algorithm>
#include <cstddef>

namespace smql::model {

// m of a seat's length one person takes (a person's width on a bench or a sofa: ANSI/BIFMA's 24 in).
inline constexpr double kSeatPlaceWidth = 0.6;

// m a walking person keeps from every obstacle, either side: a way is walkable where it is twice this wide.
inline constexpr double kBodyRadius = 0.2;

// One place for each `placeWidth` of the seat's longest side, one at least: a chair 1, a 2 m sofa 3.
inline std::size_t seatPlaces(double longestSide, double placeWidth = kSeatPlaceWidth) {
    return std::max<std::size_t>(1, static_cast<std::size_t>(longestSide / placeWidth));
}

}  // namespace smql::model
