// The sweep's CSV cells (experiments/gem_sweep.h): one field list for the header and the lines.
#include <refract/experiments/gem_sweep.h>
#include <refract/experiments/plot.h>

namespace refract::experiments::gem_sweep {
namespace {

#define REFRACT_NUMBER(NAME, EXPR) Field{NAME, [](const Row& r) { return number(EXPR); }}

std::string kinds(const Row& r) {
    std::string k;
    for (const auto& [kind, v] : r.metrics.leakage_by_kind) k += (k.empty() ? "" : ";") + kind + ":" + number(v);
    return csv_quote(k);
}

}  // namespace

const std::vector<Field>& fields() {
    static const std::vector<Field> f{
        REFRACT_NUMBER("measured_table", r.measured.table),
        REFRACT_NUMBER("measured_crown_angle", r.measured.crown_angle),
        REFRACT_NUMBER("measured_pavilion_angle", r.measured.pavilion_angle),
        REFRACT_NUMBER("measured_star", r.measured.star),
        REFRACT_NUMBER("measured_lower_half", r.measured.lower_half),
        REFRACT_NUMBER("measured_girdle", r.measured.girdle),
        REFRACT_NUMBER("crown_height", r.measured.crown_height),
        REFRACT_NUMBER("pavilion_depth", r.measured.pavilion_depth),
        REFRACT_NUMBER("total_depth", r.measured.total_depth),
        REFRACT_NUMBER("light_return", r.metrics.light_return.value),
        REFRACT_NUMBER("light_return_error", r.metrics.light_return.error),
        REFRACT_NUMBER("fire", r.metrics.fire.value),
        REFRACT_NUMBER("fire_error", r.metrics.fire.error),
        REFRACT_NUMBER("leakage", r.metrics.leakage.value),
        REFRACT_NUMBER("leakage_error", r.metrics.leakage.error),
        REFRACT_NUMBER("scintillation", r.metrics.scintillation.value),
        REFRACT_NUMBER("scintillation_error", r.metrics.scintillation.error),
        REFRACT_NUMBER("nail_head", r.metrics.nail_head.value),
        REFRACT_NUMBER("nail_head_error", r.metrics.nail_head.error),
        REFRACT_NUMBER("fish_eye", r.metrics.fish_eye.value),
        REFRACT_NUMBER("fish_eye_error", r.metrics.fish_eye.error),
        REFRACT_NUMBER("obstruction", r.metrics.obstruction.value),
        REFRACT_NUMBER("obstruction_error", r.metrics.obstruction.error),
        Field{"leakage_by_kind", kinds},
        REFRACT_NUMBER("aset_red", r.metrics.aset.red),
        REFRACT_NUMBER("aset_green", r.metrics.aset.green),
        REFRACT_NUMBER("aset_blue", r.metrics.aset.blue),
        REFRACT_NUMBER("aset_white", r.metrics.aset.white),
        REFRACT_NUMBER("balance_crown", r.metrics.balance.crown),
        REFRACT_NUMBER("balance_girdle", r.metrics.balance.girdle),
        REFRACT_NUMBER("balance_pavilion", r.metrics.balance.pavilion),
        REFRACT_NUMBER("balance_lost", r.metrics.balance.lost),
        REFRACT_NUMBER("balance_missed", r.metrics.balance.missed),
        Field{"observer", [](const Row& r) { return csv_quote(r.metrics.observer); }},
    };
    return f;
}

#undef REFRACT_NUMBER

std::string csv_header() {
    std::string h = "index,table,crown_angle,pavilion_angle,star,lower_half,girdle,status,reason";
    for (const Field& f : fields()) h += std::string(",") + f.name;
    return h;
}

std::string csv_line(const Row& r) {
    const BrilliantCut& c = r.cut;
    std::string s = std::to_string(r.index);
    for (const double v : {c.table, c.crown_angle, c.pavilion_angle, c.star, c.lower_half, c.girdle}) s += "," + number(v);
    if (!r.possible) return s + ",impossible," + csv_quote(r.reason) + std::string(fields().size(), ',');
    s += ",ok,";
    for (const Field& f : fields()) s += "," + f.cell(r);
    return s;
}

}  // namespace refract::experiments::gem_sweep
