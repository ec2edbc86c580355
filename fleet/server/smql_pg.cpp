// smql_pg.so: the predicates of relations/ inside PostgreSQL, so that the fleet store decides a
// pair with the very code the engine runs (the same formulas and default thresholds, compiled from
// relations/predicates.cpp, not a copy in SQL that could drift). The SQL functions that call it,
// one per predicate, are generated from the predicate table (fleet/predicates_sql.cpp).
//
//   smql.predicate_score(code, a, b, c, viewpoint, distance, others, thresholds) -> float8: relations::evaluate
//   smql.predicate_region(code, ref, distance, thresholds) -> float8[6]: where a candidate must lie
//   smql.relate(a, b, viewpoint, others, thresholds) -> float8[]: relations::relate, as (code, score) pairs
//   smql.box_distance(a, b) -> float8: model::distance, the gap between two boxes
//
// Nodes arrive as rows of smql.nodes; `others` are the nodes that may stand between (near's walls,
// visible_from's obstacles); `thresholds` are a session's settings in the order of
// relations::settingsCatalogue (NULL: the defaults). No C++ exception reaches PostgreSQL: errors become ereport after
// the C++ frames have unwound.
extern "C" {
#include "postgres.h"
// postgres.h first; then:
#include "catalog/pg_type.h"
#include "executor/executor.h"
#include "fmgr.h"
#include "utils/array.h"
#include "utils/builtins.h"
#include "utils/lsyscache.h"

PG_MODULE_MAGIC;
PG_FUNCTION_INFO_V1(smql_predicate_score);
PG_FUNCTION_INFO_V1(smql_predicate_region);
PG_FUNCTION_INFO_V1(smql_relate);
PG_FUNCTION_INFO_V1(smql_box_distance);
}

#include <optional>
#include <string>
#include <vector>

#include "model/geometry.hpp"
#include "relations/predicates.hpp"
#include "relations/thresholds.hpp"

namespace {

// PostgreSQL has a Node of its own.
using SmqlNode = smql::model::Node;

double realField(HeapTupleHeader row, const char* name) {
    bool isNull = false;
    Datum d = GetAttributeByName(row, name, &isNull);
    return isNull ? 0.0 : DatumGetFloat8(d);
}

int smallField(HeapTupleHeader row, const char* name) {
    bool isNull = false;
    Datum d = GetAttributeByName(row, name, &isNull);
    return isNull ? 0 : DatumGetInt16(d);
}

// A row of smql.nodes as the engine's node: what the formulas read (id, kind, category, geometry,
// box). The id is the scene-local one, which is all `a.id == b.id` needs.
SmqlNode nodeOf(HeapTupleHeader row) {
    SmqlNode n;
    bool isNull = false;
    n.id = static_cast<smql::model::NodeId>(DatumGetInt32(GetAttributeByName(row, "id", &isNull)));
    n.kind = static_cast<smql::model::NodeKind>(smallField(row, "kind"));
    n.geometry = static_cast<smql::model::GeometryKind>(smallField(row, "geometry"));
    Datum category = GetAttributeByName(row, "category", &isNull);
    if (!isNull) n.category = text_to_cstring(DatumGetTextPP(category));
    n.box = {{realField(row, "cx"), realField(row, "cy"), realField(row, "cz")},
             {realField(row, "sx"), realField(row, "sy"), realField(row, "sz")},
             realField(row, "yaw")};
    Datum hidden = GetAttributeByName(row, "hidden", &isNull);
    n.hidden = !isNull && DatumGetBool(hidden);
    return n;
}

std::vector<SmqlNode> nodesOf(ArrayType* array) {
    int16 length = 0;
    bool byValue = false;
    char align = 0;
    get_typlenbyvalalign(ARR_ELEMTYPE(array), &length, &byValue, &align);
    Datum* values = nullptr;
    bool* nulls = nullptr;
    int count = 0;
    deconstruct_array(array, ARR_ELEMTYPE(array), length, byValue, align, &values, &nulls, &count);
    std::vector<SmqlNode> out;
    out.reserve(static_cast<std::size_t>(count));
    for (int i = 0; i < count; ++i)
        if (!nulls[i]) out.push_back(nodeOf(DatumGetHeapTupleHeader(values[i])));
    return out;
}

// The view frame of a viewpoint (x, y, z, facing yaw), and a fifth number 1 when FACING gave the
// heading (VIEW FROM x FACING y); the default frame without one.
smql::relations::Frame frameOf(FunctionCallInfo fcinfo, int argument) {
    if (PG_ARGISNULL(argument)) return {};
    ArrayType* viewpoint = PG_GETARG_ARRAYTYPE_P(argument);
    const auto* data = reinterpret_cast<const double*>(ARR_DATA_PTR(viewpoint));
    const int items = ArrayGetNItems(ARR_NDIM(viewpoint), ARR_DIMS(viewpoint));
    if (ARR_ELEMTYPE(viewpoint) != FLOAT8OID || (items != 4 && items != 5)) return {};
    smql::relations::Frame frame = smql::relations::viewFrame({{data[0], data[1], data[2]}, data[3]});
    frame.headingGiven = items == 5 && data[4] != 0;
    return frame;
}

// A session's thresholds, in the settings catalogue's order (the one table of them).
smql::relations::Thresholds thresholdsOf(FunctionCallInfo fcinfo, int argument) {
    smql::relations::Thresholds thresholds;
    if (PG_ARGISNULL(argument)) return thresholds;
    ArrayType* values = PG_GETARG_ARRAYTYPE_P(argument);
    const auto& catalogue = smql::relations::settingsCatalogue();
    if (ARR_ELEMTYPE(values) != FLOAT8OID || ARR_HASNULL(values) ||
        ArrayGetNItems(ARR_NDIM(values), ARR_DIMS(values)) != static_cast<int>(catalogue.size()))
        ereport(ERROR, (errmsg("smql: thresholds are %d numbers, in the order of SHOW SETTINGS",
                               static_cast<int>(catalogue.size()))));
    const auto* data = reinterpret_cast<const double*>(ARR_DATA_PTR(values));
    for (std::size_t i = 0; i < catalogue.size(); ++i) thresholds.*(catalogue[i].field) = data[i];
    return thresholds;
}

// The nodes around a pair, read from the function's array argument the first time a formula asks for them: `on`
// asks only of a lamp's loose box or of a slab a wall may hold, so most pairs it scores never decode the scene's
// nodes (a FIND on(table) of 200 objects took 3x as long when each call decoded them all). The SQL signature fixes
// the array's type, so its decoding raises no PostgreSQL error inside the formula's C++ frames.
class ArgumentObstacles final : public smql::relations::Obstacles {
public:
    ArgumentObstacles(FunctionCallInfo call, int argument) : call_(call), argument_(argument) {}
    void within(const smql::model::Aabb& region, std::vector<const SmqlNode*>& out) const override {
        if (!obstacles_) {
            if (!call_->args[argument_].isnull) others_ = nodesOf(DatumGetArrayTypeP(call_->args[argument_].value));
            obstacles_.emplace(others_);
        }
        obstacles_->within(region, out);
    }

private:
    FunctionCallInfo call_;
    int argument_;
    mutable std::vector<SmqlNode> others_;
    mutable std::optional<smql::relations::NodeObstacles> obstacles_;
};

bool validCode(int32 code) { return code >= 0 && code < static_cast<int32>(smql::model::kRelationTypeCount); }

}  // namespace

extern "C" Datum smql_predicate_score(PG_FUNCTION_ARGS) {
    if (PG_ARGISNULL(0) || PG_ARGISNULL(1) || PG_ARGISNULL(2)) PG_RETURN_NULL();
    const int32 code = PG_GETARG_INT32(0);
    if (!validCode(code)) ereport(ERROR, (errmsg("smql: no predicate has the code %d", code)));
    double score = 0;
    std::string failure;
    try {
        const SmqlNode a = nodeOf(PG_GETARG_HEAPTUPLEHEADER(1));
        const SmqlNode b = nodeOf(PG_GETARG_HEAPTUPLEHEADER(2));
        std::optional<SmqlNode> c;
        if (!PG_ARGISNULL(3)) c = nodeOf(PG_GETARG_HEAPTUPLEHEADER(3));
        const smql::relations::Frame frame = frameOf(fcinfo, 4);
        std::optional<double> distance;
        if (!PG_ARGISNULL(5)) distance = PG_GETARG_FLOAT8(5);
        const smql::relations::Thresholds thresholds = thresholdsOf(fcinfo, 7);
        const ArgumentObstacles obstacles(fcinfo, 6);
        score = smql::relations::evaluate(static_cast<smql::relations::Predicate>(code), a, b, thresholds, frame,
                                          obstacles, c ? &*c : nullptr, distance);
    } catch (const std::exception& e) {
        failure = e.what();
    }
    if (!failure.empty()) ereport(ERROR, (errmsg("smql: %s", failure.c_str())));
    PG_RETURN_FLOAT8(score);
}

extern "C" Datum smql_predicate_region(PG_FUNCTION_ARGS) {
    if (PG_ARGISNULL(0) || PG_ARGISNULL(1)) PG_RETURN_NULL();
    const int32 code = PG_GETARG_INT32(0);
    if (!validCode(code)) ereport(ERROR, (errmsg("smql: no predicate has the code %d", code)));
    const auto& spec = smql::relations::spec(static_cast<smql::relations::Predicate>(code));
    if (!spec.candidateRegion) PG_RETURN_NULL();  // it can hold far away: no region to probe
    const smql::relations::Thresholds thresholds = thresholdsOf(fcinfo, 3);
    const SmqlNode ref = nodeOf(PG_GETARG_HEAPTUPLEHEADER(1));
    const double distance = PG_ARGISNULL(2) ? thresholds.nearDistance : PG_GETARG_FLOAT8(2);
    const smql::model::Aabb region = spec.candidateRegion(smql::model::worldAabb(ref.box), distance, thresholds);
    Datum bounds[6] = {Float8GetDatum(region.min.x), Float8GetDatum(region.min.y), Float8GetDatum(region.min.z),
                       Float8GetDatum(region.max.x), Float8GetDatum(region.max.y), Float8GetDatum(region.max.z)};
    PG_RETURN_ARRAYTYPE_P(construct_array(bounds, 6, FLOAT8OID, sizeof(float8), FLOAT8PASSBYVAL, TYPALIGN_DOUBLE));
}

extern "C" Datum smql_relate(PG_FUNCTION_ARGS) {
    if (PG_ARGISNULL(0) || PG_ARGISNULL(1)) PG_RETURN_NULL();
    std::vector<Datum> pairs;
    std::string failure;
    try {
        const SmqlNode a = nodeOf(PG_GETARG_HEAPTUPLEHEADER(0));
        const SmqlNode b = nodeOf(PG_GETARG_HEAPTUPLEHEADER(1));
        const smql::relations::Frame frame = frameOf(fcinfo, 2);
        std::vector<SmqlNode> others;
        if (!PG_ARGISNULL(3)) others = nodesOf(PG_GETARG_ARRAYTYPE_P(3));
        const smql::relations::NodeObstacles obstacles(others);
        for (const auto& hit : smql::relations::relate(a, b, thresholdsOf(fcinfo, 4), frame, obstacles)) {
            pairs.push_back(Float8GetDatum(static_cast<double>(hit.predicate)));
            pairs.push_back(Float8GetDatum(hit.score));
        }
    } catch (const std::exception& e) {
        failure = e.what();
    }
    if (!failure.empty()) ereport(ERROR, (errmsg("smql: %s", failure.c_str())));
    PG_RETURN_ARRAYTYPE_P(construct_array(pairs.data(), static_cast<int>(pairs.size()), FLOAT8OID, sizeof(float8),
                                          FLOAT8PASSBYVAL, TYPALIGN_DOUBLE));
}

extern "C" Datum smql_box_distance(PG_FUNCTION_ARGS) {
    if (PG_ARGISNULL(0) || PG_ARGISNULL(1)) PG_RETURN_NULL();
    const SmqlNode a = nodeOf(PG_GETARG_HEAPTUPLEHEADER(0));
    const SmqlNode b = nodeOf(PG_GETARG_HEAPTUPLEHEADER(1));
    PG_RETURN_FLOAT8(smql::model::distance(a.box, b.box));
}
