// Parameter studies (study/): the runs a study makes (grid and zip), the fields they set, every
// problem of a study named by its field, and the table and figure made from the runs' results.
#include <gtest/gtest.h>

#include <algorithm>

#include "study/study_table.hpp"

namespace dem::study {
namespace {

using json = nlohmann::json;

const json kBase = json::parse(R"({
  "name": "base",
  "bonds": {"tensileStrength": 1e6, "seed": 7},
  "packings": [{"seed": 3}, {"seed": 4}],
  "time": {"duration": 1}
})");

json study_with(const json& parameters, const std::string& combine = "grid") {
  return {{"name", "s"}, {"base", kBase}, {"parameters", parameters}, {"combine", combine}};
}

std::vector<std::string> problems_of(const json& study) {
  try {
    plan_study(study, json());
  } catch (const StudyError& e) {
    return e.problems();
  }
  return {};
}

bool has_problem(const json& study, const std::string& text) {
  const std::vector<std::string> p = problems_of(study);
  return std::any_of(p.begin(), p.end(), [&](const std::string& s) { return s.find(text) != std::string::npos; });
}

TEST(StudyPlan, AGridRunsEveryCombinationTheLastParameterTurningFastest) {
  const StudyPlan plan = plan_study(study_with({{{"path", "bonds.tensileStrength"}, {"values", {0, 4e6, 8e6}}},
                                                {{"path", "/packings/1/seed"}, {"values", {1, 2}}}}),
                                    json());
  ASSERT_EQ(plan.runs.size(), 6u);
  EXPECT_EQ(plan.runs[0].spec["bonds"]["tensileStrength"], 0);
  EXPECT_EQ(plan.runs[0].spec["packings"][1]["seed"], 1);
  EXPECT_EQ(plan.runs[1].spec["packings"][1]["seed"], 2);
  EXPECT_EQ(plan.runs[5].spec["bonds"]["tensileStrength"], 8e6);
  EXPECT_EQ(plan.runs[5].spec["packings"][1]["seed"], 2);
  EXPECT_EQ(plan.runs[5].spec["packings"][0]["seed"], 3);  // the rest of the base as it was
  EXPECT_EQ(plan.runs[5].spec["bonds"]["seed"], 7);
  EXPECT_EQ(plan.runs[3].spec["name"], "s #4 (bonds.tensileStrength=4000000.0, /packings/1/seed=2)");
  EXPECT_EQ(plan.runs[3].index, 4);
}

TEST(StudyPlan, AZipTakesTheKthValueOfEach) {
  const StudyPlan plan = plan_study(study_with({{{"path", "bonds.tensileStrength"}, {"values", {1, 2, 3}}},
                                                {{"path", "bonds.seed"}, {"values", {4, 5, 6}}}},
                                               "zip"),
                                    json());
  ASSERT_EQ(plan.runs.size(), 3u);
  EXPECT_EQ(plan.runs[2].spec["bonds"]["tensileStrength"], 3);
  EXPECT_EQ(plan.runs[2].spec["bonds"]["seed"], 6);
  EXPECT_TRUE(has_problem(study_with({{{"path", "bonds.tensileStrength"}, {"values", {1, 2, 3}}},
                                      {{"path", "bonds.seed"}, {"values", {4, 5}}}},
                                     "zip"),
                          "bonds.seed has 2"));
}

// The PDEM-EGD manual's one bond strength C is both the tensile and the shear strength: a parameter
// may name several fields that take each value together, and a grid crosses it with the seeds.
TEST(StudyPlan, AParameterMaySetSeveralFieldsToOneValue) {
  const StudyPlan plan =
      plan_study(study_with({{{"path", {"bonds.tensileStrength", "bonds.shearStrength"}}, {"values", {0, 4e6}}},
                             {{"path", "packings[0].seed"}, {"values", {1, 2, 3}}}}),
                 json());
  ASSERT_EQ(plan.runs.size(), 6u);
  EXPECT_EQ(plan.runs[4].spec["bonds"]["tensileStrength"], 4e6);
  EXPECT_EQ(plan.runs[4].spec["bonds"]["shearStrength"], 4e6);
  EXPECT_EQ(plan.runs[4].spec["packings"][0]["seed"], 2);
  EXPECT_EQ(plan.parameters[0].path, "bonds.tensileStrength = bonds.shearStrength");
  EXPECT_EQ(plan.runs[4].spec["name"],
            "s #5 (bonds.tensileStrength = bonds.shearStrength = 4000000.0, packings[0].seed=2)");
  EXPECT_TRUE(has_problem(study_with({{{"path", {"bonds.seed", "bonds.x.y"}}, {"values", {1}}}}),
                          "parameters[0].path[1]: \"bonds.x.y\": the base spec has no \"/bonds/x\""));
  EXPECT_TRUE(has_problem(study_with({{{"path", {"bonds.seed", "/bonds/seed"}}, {"values", {1}}}}), "varied twice"));
  EXPECT_TRUE(has_problem(study_with({{{"path", json::array()}, {"values", {1}}}}), "parameters[0].path: the field"));
  EXPECT_TRUE(has_problem(study_with({{{"path", {"bonds.seed", 3}}, {"values", {1}}}}),
                          "parameters[0].path[1]: a field's path, as text (got 3)"));
  // an independent tester: a field and the object holding it, varied at once, gave a table that said
  // the field's value while the run had the object's (the later parameter overwrote the earlier)
  EXPECT_TRUE(has_problem(study_with({{{"path", "bonds.tensileStrength"}, {"values", {7}}},
                                      {{"path", "bonds"}, {"values", {{{"tensileStrength", 5}}}}}}),
                          "parameters[1].path: \"bonds\" holds a field parameters[0].path varies: vary one of them"));
  EXPECT_TRUE(has_problem(study_with({{{"path", {"bonds", "bonds.seed"}}, {"values", {1}}}}),
                          "parameters[0].path[1]: \"bonds.seed\" is part of a field parameters[0].path[0] varies"));
  // and an index past what a number holds was answered in the JSON library's words
  EXPECT_TRUE(has_problem(study_with({{{"path", "packings[99999999999999999999].seed"}, {"values", {1}}}}),
                          "the base spec has no \"/packings/99999999999999999999\""));
}

TEST(StudyPlan, AFieldTheBaseDoesNotHaveIsAddedWhenItsParentIsThere) {
  const StudyPlan plan = plan_study(study_with({{{"path", "bonds.shearStrength"}, {"values", {5}}}}), json());
  EXPECT_EQ(plan.runs[0].spec["bonds"]["shearStrength"], 5);
}

// A field's name in the other spelling than the base's (tensile_strength, tensileStrength; a spec
// takes both) sets the base's field: set as a second key, the run's spec held it twice, refused as
// "is given twice in its object" (an independent tester). A field the base lacks keeps the spelling asked.
TEST(StudyPlan, AFieldNamedInTheOtherSpellingSetsTheBasesField) {
  const StudyPlan plan =
      plan_study(study_with({{{"path", {"bonds.tensile_strength", "/packings/1/seed"}}, {"values", {5}}},
                             {{"path", "bonds.shear_strength"}, {"values", {6}}}}),
                 json());
  ASSERT_EQ(plan.runs.size(), 1u);
  const json& bonds = plan.runs[0].spec["bonds"];
  EXPECT_EQ(bonds["tensileStrength"], 5);
  EXPECT_FALSE(bonds.contains("tensile_strength")) << bonds.dump();
  EXPECT_EQ(bonds["shear_strength"], 6);
  EXPECT_EQ(plan.runs[0].spec["packings"][1]["seed"], 5);
}

// ... in any segment of the path, not only the last (particles[0].angular_velocity.z against a base's
// angularVelocity: "the base spec has no /particles/0/angular_velocity"; an independent tester). Only
// the two spellings the spec's parser takes count: "normalstiffness" is not normalStiffness (it is
// set as asked, and the run's spec check names it as an unknown field).
TEST(StudyPlan, EverySegmentOfAPathFindsTheBasesFieldByEitherSpellingTheParserTakes) {
  const json base = json::parse(R"({"particles": [{"angularVelocity": {"z": 1}, "radius": 0.01}],
                                    "materials": [{"normalStiffness": 1e5, "poisson_ratio": 0.2}]})");
  const json study = {{"name", "s"},
                      {"base", base},
                      {"parameters",
                       {{{"path", "particles[0].angular_velocity.z"}, {"values", {2}}},
                        {{"path", "materials[0].poissonRatio"}, {"values", {0.3}}},
                        {{"path", "materials[0].normalstiffness"}, {"values", {3e5}}}}}};
  const StudyPlan plan = plan_study(study, json());
  ASSERT_EQ(plan.runs.size(), 1u);
  const json& spec = plan.runs[0].spec;
  EXPECT_EQ(spec["particles"][0]["angularVelocity"]["z"], 2) << spec.dump();
  EXPECT_FALSE(spec["particles"][0].contains("angular_velocity")) << spec.dump();
  EXPECT_EQ(spec["materials"][0]["poisson_ratio"], 0.3) << spec.dump();
  EXPECT_FALSE(spec["materials"][0].contains("poissonRatio")) << spec.dump();
  EXPECT_EQ(spec["materials"][0]["normalStiffness"], 1e5) << spec.dump();
  EXPECT_EQ(spec["materials"][0]["normalstiffness"], 3e5) << spec.dump();
}

// Two spellings of one field the base does not have are one field varied twice (each run's spec
// held it twice, refused run by run).
TEST(StudyPlan, TwoSpellingsOfAFieldTheBaseLacksAreVariedTwice) {
  EXPECT_TRUE(has_problem(
      study_with({{{"path", "time.dt_fraction"}, {"values", {0.1}}}, {{"path", "time.dtFraction"}, {"values", {0.2}}}}),
      "varied twice"));
}

TEST(StudyPlan, EveryProblemIsNamedByItsField) {
  EXPECT_TRUE(has_problem(study_with({{{"path", "bonds.x.y"}, {"values", {1}}}}), "parameters[0].path"));
  EXPECT_TRUE(has_problem(study_with({{{"path", "bonds.x.y"}, {"values", {1}}}}), "has no \"/bonds/x\""));
  EXPECT_TRUE(has_problem(study_with({{{"path", "packings[5]"}, {"values", {1}}}}), "has 2 entries"));
  EXPECT_TRUE(has_problem(study_with({{{"path", "packings[5].seed"}, {"values", {1}}}}), "has no \"/packings/5\""));
  EXPECT_TRUE(has_problem(study_with({{{"path", "time.duration.x"}, {"values", {1}}}}), "is a value"));
  EXPECT_TRUE(has_problem(study_with({{{"path", "bonds.seed"}, {"values", json::array()}}}), "parameters[0].values"));
  EXPECT_TRUE(
      has_problem(study_with({{{"path", "bonds.seed"}, {"values", {1}}}, {{"path", "/bonds/seed"}, {"values", {2}}}}),
                  "varied twice"));
  EXPECT_TRUE(
      has_problem(study_with({{{"path", "bonds.seed"}, {"value", {1}}}}), "parameters[0].value: unknown field"));
  EXPECT_TRUE(has_problem(study_with({{{"path", "a[x]"}, {"values", {1}}}}), "parameters[0].path: not a field's path"));
  EXPECT_TRUE(has_problem(study_with(json::array()), "parameters: a non-empty list"));
  EXPECT_TRUE(has_problem(study_with({{{"path", "bonds.seed"}, {"values", {1}}}}, "cross"), "combine:"));
  json no_base = study_with({{{"path", "bonds.seed"}, {"values", {1}}}});
  no_base.erase("base");
  EXPECT_TRUE(has_problem(no_base, "base: missing"));
  json typo = study_with({{{"path", "bonds.seed"}, {"values", {1}}}});
  typo["parameter"] = 1;
  EXPECT_TRUE(has_problem(typo, "parameter: unknown field"));
  // a grid too large to run
  json big = study_with({{{"path", "bonds.seed"}, {"values", json(std::vector<int>(200, 1))}},
                         {{"path", "bonds.tensileStrength"}, {"values", json(std::vector<int>(200, 1))}}});
  EXPECT_TRUE(has_problem(big, "40000 runs, more than a study may have (10000)"));
  EXPECT_TRUE(has_problem(json::array(), "a study is a JSON object"));
}

TEST(StudyPlan, DottedPathsAreJsonPointers) {
  EXPECT_EQ(to_pointer("bonds.tensileStrength"), "/bonds/tensileStrength");
  EXPECT_EQ(to_pointer("packings[0].seed"), "/packings/0/seed");
  EXPECT_EQ(to_pointer("walls[2].load.fMax"), "/walls/2/load/fMax");
  EXPECT_EQ(to_pointer("/a/0/b"), "/a/0/b");
  EXPECT_THROW(to_pointer("a..b"), std::invalid_argument);
  EXPECT_THROW(to_pointer("a[]"), std::invalid_argument);
  EXPECT_THROW(to_pointer("a."), std::invalid_argument);
  EXPECT_THROW(to_pointer(""), std::invalid_argument);
  EXPECT_THROW(to_pointer("/"),
               std::invalid_argument);  // the field "" (the spec then said "Proto fields must have a name")
  EXPECT_THROW(to_pointer("/a//b"), std::invalid_argument);
}

json results(double runout, int fragments) {
  return {{"status", "completed"},
          {"motion", {{"runout", {{"length", runout}}}, {"centreOfMass", {{"end", {1, 2, 3}}}}}},
          {"fragments", {{"count", fragments}, {"sizes", {{{"fragments", 1}}}}}},
          {"loadedWalls", {{{"wall", "sleeper"}, {"permanentSettlement", 0.01}, {"cycles", {{{"cycle", 1}}}}}}},
          {"sources", {{{"name", "sand"}, {"mass", 2.0}, {"heights", {{{"fraction", 0}, {"height", 0.1}}}}}}}};
}

TEST(StudyTable, OneRowPerRunWithItsValuesAndItsResults) {
  const StudyPlan plan = plan_study(study_with({{{"path", "bonds.tensileStrength"}, {"values", {1, 2}}},
                                                {{"path", "bonds.seed"}, {"values", {"a,b", "c"}}}}),
                                    json());
  std::vector<StudyRow> rows;
  for (const StudyRun& run : plan.runs) rows.push_back(row_of(run));
  rows[0].state = "succeeded";
  rows[0].results = results(10, 3);
  rows[1].state = "failed";
  rows[1].error = "unstable";
  const std::string csv = table_csv(plan, rows);
  const std::string header = csv.substr(0, csv.find('\n'));
  EXPECT_EQ(header.substr(0, 49), "run,bonds.tensileStrength,bonds.seed,state,error,");
  EXPECT_NE(header.find("motion.runout.length"), std::string::npos) << header;
  EXPECT_NE(header.find("motion.centreOfMass.end.2"), std::string::npos) << header;
  EXPECT_NE(header.find("loadedWalls.0.permanentSettlement"), std::string::npos) << header;
  EXPECT_NE(header.find("sources.0.mass"), std::string::npos) << header;  // a sand mass put in
  EXPECT_EQ(header.find("cycles"), std::string::npos) << header;          // left to the JSON table
  EXPECT_EQ(header.find("heights"), std::string::npos) << header;
  EXPECT_EQ(header.find("sizes"), std::string::npos) << header;
  EXPECT_NE(csv.find("\n1,1,\"a,b\",succeeded,,"), std::string::npos) << csv;  // a comma quoted
  EXPECT_NE(csv.find("\n2,1,c,failed,unstable"), std::string::npos) << csv;
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 5);

  const json table = table_json(plan, rows);
  EXPECT_EQ(table["rows"].size(), 4u);
  EXPECT_EQ(table["rows"][0]["parameters"]["bonds.seed"], "a,b");
  EXPECT_EQ(table["rows"][0]["results"]["fragments"]["count"], 3);
  EXPECT_EQ(table["rows"][3]["state"], "not run");
  EXPECT_EQ(table["plot"], json({"motion.runout.length", "fragments.count", "loadedWalls.0.permanentSettlement"}));
}

TEST(StudyTable, TheFigureHasAPanelPerResultAndAPointPerRun) {
  const StudyPlan plan = plan_study(study_with({{{"path", "bonds.tensileStrength"}, {"values", {0, 4, 8}}},
                                                {{"path", "bonds.seed"}, {"values", {1, 2}}}}),
                                    json());
  std::vector<StudyRow> rows;
  for (const StudyRun& run : plan.runs) {
    rows.push_back(row_of(run));
    rows.back().results = results(10 - run.values[0].get<double>(), run.index);
    rows.back().state = "succeeded";
  }
  rows[5].results = nullptr;  // not done yet
  rows[5].state = "running";
  // a run stopped by the guard has a results.json too, which is not its values' outcome: not a point
  rows[4].state = "failed";
  const std::string svg = figure_svg(plan, rows);
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  // three panels (runout, fragments, settlement), five runs with results in each
  auto count = [&](const std::string& what) {
    std::size_t n = 0;
    for (std::size_t at = svg.find(what); at != std::string::npos; at = svg.find(what, at + 1)) ++n;
    return n;
  };
  EXPECT_EQ(count("<circle"), 12u);
  EXPECT_EQ(count("<polyline"), 3u);
  EXPECT_NE(svg.find("4 of 6 runs (those that succeeded)"), std::string::npos);
  EXPECT_NE(svg.find(">motion.runout.length<"), std::string::npos);
  EXPECT_NE(svg.find(">bonds.tensileStrength<"), std::string::npos);
}

// A study of strengths in pascals (0 to 16 MPa): its x labels ran into each other ("1.2e+07" every
// 2e+06 over 280 px). They are short (4e6) and each clears the one before.
TEST(StudyTable, TickLabelsAreShortAndDoNotOverlap) {
  const StudyPlan plan =
      plan_study(study_with({{{"path", "bonds.tensileStrength"}, {"values", {0, 4e6, 8e6, 12e6, 16e6}}}}), json());
  std::vector<StudyRow> rows;
  for (const StudyRun& run : plan.runs) {
    rows.push_back(row_of(run));
    rows.back().results = results(run.values[0].get<double>() / 1e6, run.index);
    rows.back().state = "succeeded";
  }
  const std::string svg = figure_svg(plan, rows);
  EXPECT_EQ(svg.find("e+0"), std::string::npos);
  EXPECT_NE(svg.find("e6<"), std::string::npos) << "as 4e6";
  // the x labels of the first panel: text-anchor middle, under the plot
  std::vector<std::pair<double, std::size_t>> labels;  // centre, characters
  const std::string first = svg.substr(0, svg.find("</text>", svg.find(">bonds.tensileStrength<")));
  for (std::size_t at = first.find("text-anchor=\"middle\">"); at != std::string::npos;
       at = first.find("text-anchor=\"middle\">", at + 1)) {
    const std::size_t x = first.rfind("x=\"", at) + 3;
    const std::size_t begin = at + 21, end = first.find('<', begin);
    labels.emplace_back(std::stod(first.substr(x)), end - begin);
  }
  ASSERT_GE(labels.size(), 3u);
  labels.pop_back();  // the axis's name
  for (std::size_t k = 1; k < labels.size(); ++k)
    EXPECT_GE(labels[k].first - labels[k - 1].first, 3.5 * (labels[k].second + labels[k - 1].second))
        << "labels " << k - 1 << " and " << k;
}

}  // namespace
}  // namespace dem::study
