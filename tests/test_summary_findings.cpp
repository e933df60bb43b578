// The sentences of the experiments' summaries that state a finding or compare with a paper:
// each is chosen by a predicate on the Result's numbers (`judge`), and worded the other way
// when the numbers say otherwise. Every test builds a Result by hand on both sides of one
// predicate and checks the predicate and the wording.
#include <catch2/catch.hpp>

#include <string>

#include <refract/experiments/birefringence.h>
#include <refract/experiments/gem_cuts.h>
#include <refract/experiments/polarisation.h>
#include <refract/experiments/rtiow.h>
#include <refract/experiments/yasuda1984.h>

using namespace refract;
using namespace refract::experiments;
using Catch::Contains;

namespace {

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// ---- yasuda1984 --------------------------------------------------------------------------

yasuda1984::NodeCost node(const std::string& formulation, const std::string& model, std::uint64_t mul) {
    yasuda1984::NodeCost c{formulation, model, {}};
    c.ops.mul = mul;
    return c;
}

// A Result whose every yasuda1984 finding holds (the numbers of a real run, rounded).
yasuda1984::Result yasuda_as_measured() {
    yasuda1984::Result r;
    r.fig4 = {{0, 0.04, 0.04, 0.04}, {90, 1, 1, 1}};
    r.rs_rp_gap_40 = 0.055;
    r.peaks = {{3, 0, 0.75, 0.75, false}, {5, 72.3, 0.62, 0.56, true}, {10, 80.1, 0.53, 0.33, true}};
    r.peak_onset = r.onset_closed_form = 3.7320508;
    r.peak_beyond_70 = 4.6;
    r.critical = {{0.2, 11.54}};
    r.fig7 = {{0.2, 0, 0.56}, {0.2, 5, 0.58}, {0.2, 11.54, 0}, {0.2, 20, 0}, {0.1, 0, 0.33}, {0.1, 4, 0.35}};
    r.wall_distance = 4;
    r.fig8.resize(3);
    r.fig8[0].value = 1.52, r.fig8[0].focus = 1.52 / 1.04;
    r.fig8[1].value = 0.8, r.fig8[1].focus = -2, r.fig8[1].tir_share = 0.36;
    r.fig8[2].value = 0.1, r.fig8[2].focus = -0.056, r.fig8[2].tir_share = 0.99;
    r.R0_n5 = 0.444, r.R0_n10 = 0.669;
    r.glass_R0 = 0.0426, r.glass_R80 = 0.39;
    auto& c = r.cost;
    c.node_costs = {node("yasuda1984", "constant", 32), node("yasuda1984", "fresnel", 46)};
    c.sphere_test.mul = 8;
    c.plane_test.mul = 7;
    c.render_best[0] = 0.1003, c.render_best[1] = 0.1001;
    c.render_stats[0].segments = c.render_stats[1].segments = 888496;
    c.memory.resize(3);
    for (size_t k = 0; k < 3; ++k) {
        c.memory[k].max_depth = static_cast<int>(k) + 1;
        c.memory[k].whitted.peak_list = 100 * (k + 1);
        c.memory[k].list_threshold0.peak_list = 40 * (k + 1);
        c.memory[k].list_threshold_1_255.peak_list = k == 0 ? 2 : 3;
    }
    r.findings = yasuda1984::judge(r);
    return r;
}

}  // namespace

TEST_CASE("yasuda1984 summary: every finding holds on the numbers of a real run", "[findings][yasuda1984]") {
    const auto f = yasuda1984::judge(yasuda_as_measured());
    CHECK(f.rs_rp_close_below_40);
    CHECK(f.R_one_at_grazing);
    CHECK(f.paper_peak_holds);
    CHECK(f.onset_is_closed_form);
    CHECK(f.peak_moves_to_grazing);
    CHECK(f.low_n_rise);
    CHECK(f.zero_beyond_critical);
    CHECK(f.lenses_as_described);
    CHECK(f.mirror_rim_and_whole);
    CHECK(f.high_n_mirror_like);
    CHECK(f.fresnel_rim_brightens);
    CHECK(f.count_about_40);
    CHECK(f.test_about_quarter);
    CHECK(f.identical_trees);
    CHECK(f.measured_below_counted);
    CHECK(f.list_about_half_tree);
    CHECK(f.threshold_list_flat);
}

TEST_CASE("yasuda1984 Fig. 4: 'R rises to 1' and the paper's 'Rs or Rp alone changes little' follow R(90) and Rs - Rp at 40",
          "[findings][yasuda1984]") {
    auto r = yasuda_as_measured();
    CHECK_THAT(yasuda1984::fig4_text(r), Contains("R rises to 1 at grazing incidence") && Contains("As the paper notes"));
    r.fig4.back().R = 0.9;
    r.rs_rp_gap_40 = 0.2;
    r.findings = yasuda1984::judge(r);
    CHECK_FALSE(r.findings.R_one_at_grazing);
    CHECK_FALSE(r.findings.rs_rp_close_below_40);
    const std::string t = yasuda1984::fig4_text(r);
    CHECK_FALSE(has(t, "rises to 1"));
    CHECK_THAT(t, Contains("R reaches 0.9") && Contains("which is not little"));
    CHECK_FALSE(has(t, "As the paper notes"));
}

TEST_CASE("yasuda1984 Fig. 7: the paper's peak above 70 degrees for n >= 5 holds only when both peaks lie there",
          "[findings][yasuda1984]") {
    auto r = yasuda_as_measured();
    CHECK_THAT(yasuda1984::fig7_text(r), Contains("So the paper's statement holds for n ≳ 5"));
    r.peaks[1].angle_deg = 60;
    r.findings = yasuda1984::judge(r);
    CHECK_FALSE(r.findings.paper_peak_holds);
    CHECK_THAT(yasuda1984::fig7_text(r), Contains("does not hold for n ≳ 5"));
}

TEST_CASE("yasuda1984 Fig. 7: the onset is called the closed form's only when it matches 2 + sqrt 3",
          "[findings][yasuda1984]") {
    auto r = yasuda_as_measured();
    CHECK_FALSE(has(yasuda1984::fig7_text(r), "misses"));
    r.peak_onset = 3.9;
    r.findings = yasuda1984::judge(r);
    CHECK_FALSE(r.findings.onset_is_closed_form);
    CHECK_THAT(yasuda1984::fig7_text(r), Contains("which the measured onset (3.9) misses"));
}

TEST_CASE("yasuda1984 Fig. 7: the maximum moves towards grazing incidence only when the peak angles grow with n",
          "[findings][yasuda1984]") {
    auto r = yasuda_as_measured();
    CHECK_THAT(yasuda1984::fig7_text(r), Contains("moves quickly from 0° towards grazing"));
    r.peaks[2].angle_deg = 50;
    r.findings = yasuda1984::judge(r);
    CHECK_FALSE(r.findings.peak_moves_to_grazing);
    CHECK_THAT(yasuda1984::fig7_text(r), Contains("does not move steadily towards grazing"));
}

TEST_CASE("yasuda1984 Fig. 7: the n = 0.2 and 0.1 curves 'rise before their critical angles' only when T grows",
          "[findings][yasuda1984]") {
    auto r = yasuda_as_measured();
    CHECK_THAT(yasuda1984::fig7_text(r), Contains("which is why the n = 0.2 and 0.1 curves"));
    r.fig7[1].T = 0.5;  // n = 0.2 falls from 0°
    r.findings = yasuda1984::judge(r);
    CHECK_FALSE(r.findings.low_n_rise);
    CHECK_THAT(yasuda1984::fig7_text(r), Contains("do not rise before their critical angles"));
}

TEST_CASE("yasuda1984 Fig. 7: 'T = 0 beyond the critical angle' only when every n < 1 row there is 0",
          "[findings][yasuda1984]") {
    auto r = yasuda_as_measured();
    CHECK_THAT(yasuda1984::fig7_text(r), Contains("For n < 1, T = 0 beyond the critical angle arcsin n (n = 0.2: 11.54°)"));
    r.fig7[3].T = 0.01;
    r.findings = yasuda1984::judge(r);
    CHECK_FALSE(r.findings.zero_beyond_critical);
    CHECK_THAT(yasuda1984::fig7_text(r), Contains("T should be 0 beyond the critical angle arcsin n, but is not"));
}

TEST_CASE("yasuda1984 Fig. 8: the spheres as lenses, the mirror rim and the metallic look follow focus, TIR share and R(0)",
          "[findings][yasuda1984]") {
    auto r = yasuda_as_measured();
    std::string t = yasuda1984::fig8_text(r);
    CHECK_THAT(t, Contains("Refraction turns the floor and wall upside down") &&
                      Contains("makes its rim (n = 0.8) or nearly all of it (n = 0.1) a mirror") &&
                      Contains("look increasingly metallic"));
    r.fig8[0].focus = 5;  // behind the wall: not inverted
    r.fig8[1].tir_share = 0.6;
    r.R0_n5 = 0.1;
    r.findings = yasuda1984::judge(r);
    CHECK_FALSE(r.findings.lenses_as_described);
    CHECK_FALSE(r.findings.mirror_rim_and_whole);
    CHECK_FALSE(r.findings.high_n_mirror_like);
    t = yasuda1984::fig8_text(r);
    CHECK_THAT(t, Contains("Not every sphere focuses") && Contains("total reflection covers 0.6 of the disc at n = 0.8") &&
                      Contains("reflect at normal incidence"));
    CHECK_FALSE(has(t, "upside down inside the sphere for n > 1;"));
    CHECK_FALSE(has(t, "metallic"));
}

TEST_CASE("yasuda1984 Fig. 9: 'the rim does not brighten' against Fresnel only when Fresnel's rim reflects twice the centre",
          "[findings][yasuda1984]") {
    auto r = yasuda_as_measured();
    CHECK_THAT(yasuda1984::fig9_text(r), Contains("loss of transparent quality"));
    r.glass_R80 = 0.05;
    r.findings = yasuda1984::judge(r);
    CHECK_FALSE(r.findings.fresnel_rim_brightens);
    CHECK_THAT(yasuda1984::fig9_text(r), Contains("loses little of the transparent quality"));
}

TEST_CASE("yasuda1984 cost: the count agrees with the paper's 'about 40 %' only for a 30-50 % increase",
          "[findings][yasuda1984]") {
    auto r = yasuda_as_measured();
    CHECK_THAT(yasuda1984::cost_text(r), Contains("the count agrees with its \"about 40 %\""));
    r.cost.node_costs[1].ops.mul = 64;  // +100 %
    r.findings = yasuda1984::judge(r);
    CHECK_FALSE(r.findings.count_about_40);
    CHECK_THAT(yasuda1984::cost_text(r), Contains("the count (+100 %) does not agree"));
}

TEST_CASE("yasuda1984 cost: a sphere test is 'a quarter of the node' only at 20-30 % of it", "[findings][yasuda1984]") {
    auto r = yasuda_as_measured();
    CHECK_THAT(yasuda1984::cost_text(r), Contains("a quarter of the node"));
    r.cost.sphere_test.mul = 16;
    r.findings = yasuda1984::judge(r);
    CHECK_FALSE(r.findings.test_about_quarter);
    CHECK_THAT(yasuda1984::cost_text(r), Contains("0.5 of the node"));
}

TEST_CASE("yasuda1984 cost: the timed renders' trees are called identical only with equal segments and nodes",
          "[findings][yasuda1984]") {
    auto r = yasuda_as_measured();
    CHECK(yasuda1984::trees_text(r) == "identical trees");
    r.cost.render_stats[1].segments += 1;
    r.findings = yasuda1984::judge(r);
    CHECK_FALSE(r.findings.identical_trees);
    CHECK(yasuda1984::trees_text(r) == "trees of different size");
}

TEST_CASE("yasuda1984 cost: the paper's conclusion 'holds even more strongly' only when the measured increase is below "
          "the counted one",
          "[findings][yasuda1984]") {
    auto r = yasuda_as_measured();
    CHECK_THAT(yasuda1984::time_text(r), Contains("holds even more strongly"));
    r.cost.render_best[1] = 0.15;  // +50 %, above the counted +22.6 % per segment
    r.findings = yasuda1984::judge(r);
    CHECK_FALSE(r.findings.measured_below_counted);
    const std::string t = yasuda1984::time_text(r);
    CHECK_FALSE(has(t, "holds even more strongly"));
    CHECK_THAT(t, Contains("is not below the counted one per ray segment (+22.6 %)"));
}

TEST_CASE("yasuda1984 memory: 'about half of the tree' and 'a few entries whatever the depth' follow the lists' peaks",
          "[findings][yasuda1984]") {
    auto r = yasuda_as_measured();
    std::string t = yasuda1984::memory_text(r);
    CHECK_THAT(t, Contains("is about half of it") && Contains("the list stays at a few entries whatever the depth limit"));
    r.cost.memory.back().list_threshold0.peak_list = 10;      // 10 of 300
    r.cost.memory.back().list_threshold_1_255.peak_list = 9;  // still growing
    r.findings = yasuda1984::judge(r);
    CHECK_FALSE(r.findings.list_about_half_tree);
    CHECK_FALSE(r.findings.threshold_list_flat);
    t = yasuda1984::memory_text(r);
    CHECK_THAT(t, Contains("here 10 entries against the stored tree's 300 nodes at depth 3") &&
                      Contains("the list still grows with the depth limit (9 entries at depth 3)"));
    CHECK_FALSE(has(t, "about half of it,"));
}

// ---- rtiow-dielectric ----------------------------------------------------------------------

namespace {

rtiow::Result rtiow_as_measured() {
    rtiow::Result r;
    for (const auto& s : rtiow::stages()) {
        rtiow::StageResult st;
        st.stage = s;
        st.tir_nodes = s.id == "fig1_29_hollow" ? 5000 : 0;
        r.stages.push_back(st);
    }
    rtiow::SchlickCase c;
    c.rows = {{0, 0.04, 0.04}, {60, 1, 1}};
    r.schlick.push_back(c);
    r.convergence.rows = {{1, 0.1, 0}, {4, 0.05, 0}};
    r.convergence.fit.slope = -0.49;
    r.findings = rtiow::judge(r);
    return r;
}

}  // namespace

TEST_CASE("rtiow summary: 'TIR never occurs' in the solid sphere only when its stages count no TIR node",
          "[findings][rtiow]") {
    auto r = rtiow_as_measured();
    CHECK(r.findings.solid_without_tir);
    CHECK_THAT(rtiow::tir_text(r), Contains("so TIR never occurs and listings 1.51 and 1.54 give the same image"));
    r.stages[0].tir_nodes = 3;
    r.findings = rtiow::judge(r);
    CHECK_FALSE(r.findings.solid_without_tir);
    const std::string t = rtiow::tir_text(r);
    CHECK_FALSE(has(t, "TIR never occurs"));
    CHECK_THAT(t, Contains("yet the pixel-centre trees of the solid sphere's stages below meet TIR"));
}

TEST_CASE("rtiow summary: 'the hollow sphere is where TIR occurs' only when its stage counts TIR nodes",
          "[findings][rtiow]") {
    auto r = rtiow_as_measured();
    CHECK(r.findings.hollow_with_tir);
    CHECK_THAT(rtiow::hollow_text(r), Contains("The hollow sphere is where TIR occurs"));
    r.stages.back().tir_nodes = 0;
    r.findings = rtiow::judge(r);
    CHECK_FALSE(r.findings.hollow_with_tir);
    CHECK_THAT(rtiow::hollow_text(r), Contains("meet no TIR either"));
}

TEST_CASE("rtiow summary: 'beyond the critical angle both are 1' only when Schlick is 1 wherever Fresnel is",
          "[findings][rtiow]") {
    auto r = rtiow_as_measured();
    CHECK(rtiow::schlick_text(r) == "Beyond the critical angle both are 1 (the tracer folds TIR in). ");
    r.schlick[0].rows[1].schlick = 0.7;
    r.findings = rtiow::judge(r);
    CHECK_FALSE(r.findings.schlick_one_at_tir);
    CHECK_THAT(rtiow::schlick_text(r), Contains("Schlick is not 1 in every row"));
}

TEST_CASE("rtiow summary: 'its error falls like 1/sqrt(spp)' only for a slope within 0.1 of -1/2", "[findings][rtiow]") {
    auto r = rtiow_as_measured();
    CHECK_THAT(rtiow::convergence_text(r), Contains("**-0.49**") && Contains("unbiased estimator of the tree"));
    r.convergence.fit.slope = -0.2;
    r.findings = rtiow::judge(r);
    CHECK_FALSE(r.findings.slope_one_half);
    const std::string t = rtiow::convergence_text(r);
    CHECK_THAT(t, Contains("does not fall like 1/√spp here"));
    CHECK_FALSE(has(t, "is an unbiased estimator"));
}

// ---- polarisation --------------------------------------------------------------------------

TEST_CASE("polarisation summary: a scene 'rendered by this same walk' only when the sums over depth equal its renders'",
          "[findings][polarisation]") {
    polarisation::Result r;
    r.diamond.spectral = true;
    r.glass.title = "glass sphere";
    r.glass.light_natural = r.glass.depth_natural = 1234.5;
    r.glass.light_exact = r.glass.depth_exact = 1200.25;
    r.findings = polarisation::judge(r);
    CHECK(r.findings.glass_depth_sums_match);
    CHECK_FALSE(r.findings.diamond_depth_sums_match);  // spectral: a different walk
    CHECK(polarisation::depth_sums_text(r, r.diamond).empty());
    CHECK_THAT(polarisation::depth_sums_text(r, r.glass), Contains("The glass sphere is rendered by this same walk"));
    r.glass.depth_exact = 1100;
    r.findings = polarisation::judge(r);
    CHECK_FALSE(r.findings.glass_depth_sums_match);
    CHECK_THAT(polarisation::depth_sums_text(r, r.glass), Contains("yet the sums over depth differ"));
}

TEST_CASE("polarisation summary: the clipping 'breaks the sums' and 'the same cause' only when channels deviate",
          "[findings][polarisation]") {
    polarisation::Result r;
    r.analyser.deviating_channels = 12;
    r.analyser.dolp_above_one = 2;
    r.analyser.channels_outside_cone = 7;
    r.findings = polarisation::judge(r);
    CHECK(r.findings.clipping_deviates);
    CHECK(r.findings.outside_cone);
    CHECK_THAT(polarisation::clipping_text(r), Contains("which breaks the sums where it acts: 12 pixel channels"));
    CHECK_THAT(polarisation::cone_text(r), Contains("The same cause") && Contains("7 pixel channels"));
    r.analyser.deviating_channels = 0;
    r.analyser.dolp_above_one = 0;
    r.analyser.channels_outside_cone = 0;
    r.findings = polarisation::judge(r);
    CHECK_FALSE(r.findings.clipping_deviates);
    CHECK_FALSE(r.findings.outside_cone);
    CHECK_THAT(polarisation::clipping_text(r), Contains("no pixel channel deviates by more than 1e-9"));
    CHECK_FALSE(has(polarisation::clipping_text(r), "which breaks"));
    CHECK_THAT(polarisation::cone_text(r), Contains("lies in the cone"));
    CHECK_FALSE(has(polarisation::cone_text(r), "The same cause"));
}

// ---- birefringence -------------------------------------------------------------------------

TEST_CASE("birefringence summary: 'the line appears twice' and 'polarised at right angles' follow the plate's profiles",
          "[findings][birefringence]") {
    birefringence::Result r;
    r.plate.bright_runs = 2;
    r.plate.o_intensity = {0.8, 0.01, 0.8};
    r.plate.e_intensity = {0.7, 0.7, 0.02};
    r.findings = birefringence::judge(r);
    CHECK(r.findings.line_doubled);
    CHECK(r.findings.crossed_images);
    CHECK(birefringence::doubling_text(r) == "the line appears twice.");
    CHECK_THAT(birefringence::analyser_text(r), Contains("the two images are polarised at right angles"));
    r.plate.o_intensity[1] = 0.5;  // the ordinary image stays through the 0° analyser
    r.findings = birefringence::judge(r);
    CHECK_FALSE(r.findings.crossed_images);
    CHECK_THAT(birefringence::analyser_text(r), Contains("keeps 0.625 of its brightness") &&
                                                    Contains("does not show two images polarised at right angles"));
    r.plate.bright_runs = 1;
    r.findings = birefringence::judge(r);
    CHECK_FALSE(r.findings.line_doubled);
    CHECK_THAT(birefringence::doubling_text(r), Contains("1 bright run(s)"));
}

// ---- gem-cuts ------------------------------------------------------------------------------

TEST_CASE("gem-cuts summary: Tolkowsky's and GIA's marks are 'the same angles' only when both angles agree",
          "[findings][gem-cuts]") {
    gem_cuts::Result r;
    gem_sweep::Row tolk, gia;
    tolk.cut = brilliant_preset("tolkowsky");
    gia.cut = brilliant_preset("gia-default");
    r.presets = {{"tolkowsky", tolk}, {"gia-default", gia}};
    r.findings = gem_cuts::judge(r);
    CHECK(r.findings.presets_share_angles);
    CHECK(gem_cuts::marks_text(r) == "(the same angles, table 57 % against 53 %)");
    r.presets[1].second.cut.pavilion_angle = 41.5;
    r.findings = gem_cuts::judge(r);
    CHECK_FALSE(r.findings.presets_share_angles);
    CHECK(gem_cuts::marks_text(r) == "(crown 34.5°, pavilion 41.5°, table 57 %, against Tolkowsky's 34.5°, 40.75°, 53 %)");
}
