// One canonical name per category (model/category.hpp): however a file or a person writes it.
#include <catch2/catch.hpp>

#include "model/category.hpp"
#include "model/types.hpp"

using smql::model::categoryName;
using smql::model::categoryWords;
using smql::model::singularWord;

TEST_CASE("case, spaces, hyphens, underscores and plurals fold to one name", "[category]") {
    for (const char* written : {"trash can", "Trash_Can", "trash-can", "trash cans", "  TRASH   CAN ", "trash--can",
                                "trash_-_cans", "Trash Cans"})
        CHECK(categoryName(written) == "trash-can");
    CHECK(categoryName("computer mice") == "computer-mouse");
    CHECK(categoryName("Washing Machines") == "washing-machine");
    CHECK(categoryName("wall-plug") == "wall-plug");
    CHECK(categoryName("indoor-plant") == "indoor-plant");
    CHECK(categoryName("").empty());
    CHECK(categoryName(" - ").empty());
}

TEST_CASE("the last word's plural is its singular, by English endings and a table", "[category]") {
    CHECK(singularWord("chairs") == "chair");
    CHECK(singularWord("shelves") == "shelf");
    CHECK(singularWord("stoves") == "stove");
    CHECK(singularWord("switches") == "switch");
    CHECK(singularWord("boxes") == "box");
    CHECK(singularWord("batteries") == "battery");
    CHECK(singularWord("vases") == "vase");
    CHECK(singularWord("tvs") == "tv");
    CHECK(singularWord("people") == "person");
    CHECK(singularWord("it's") == "it's");  // a possessive or a contraction is no plural
    // Singular words that end in s, and things without a singular, stay as written.
    for (const char* kept : {"mattress", "cactus", "blinds", "glasses", "bus", "lens", "tennis", "chair", "sofa"})
        CHECK(singularWord(kept) == kept);
    // Only the last word is a plural: "glasses case" keeps its first word.
    CHECK(categoryName("glasses cases") == "glasses-case");
}

TEST_CASE("a name is canonical exactly when categoryName leaves it as it is", "[category]") {
    // isCategoryName answers without folding: every way a name can differ from its fold is here,
    // each word alone and as the last of two.
    for (const char* word :
         {"",          "-",         "chair",      "chairs",  "Chair",  "shelves",   "shelf",     "batteries",
          "battery",   "boxes",     "box",        "glasses", "glass",  "mattress",  "cactus",    "lens",
          "lenses",    "mice",      "people",     "person",  "it's",   "tvs",       "bus",       "ies",
          "xies",      "sss",       "as",         "is",      "us",     "es",        "s",         "caf\xc3\xa9s",
          "trash can", "trash_can", "trash--can", "-chair",  "chair-", "trash-can", "TRASH-CAN", "a\tb",
          "zombies",   "zombie",    "canvases",   "canvas"}) {
        for (const std::string& written : {std::string(word), std::string("wall-") + word}) {
            INFO("'" << written << "'");
            CHECK(smql::model::isCategoryName(written) == (categoryName(written) == written));
        }
    }
}

TEST_CASE("a scene's nodes get canonical names, the scene node keeps its name", "[category]") {
    smql::model::SceneData scene;
    smql::model::Node root, bin, plant;
    root.kind = smql::model::NodeKind::Scene, root.category = "My Room";
    bin.kind = smql::model::NodeKind::Object, bin.category = "Trash Cans";
    plant.kind = smql::model::NodeKind::Object, plant.category = "indoor-plant";
    scene.nodes = {root, bin, plant};
    smql::model::canonicaliseCategories(scene);
    CHECK(scene.nodes[0].category == "My Room");
    CHECK(scene.nodes[1].category == "trash-can");
    CHECK(scene.nodes[2].category == "indoor-plant");
}

TEST_CASE("a LIKE pattern over categories folds case and spaces, not its wildcards or plurals", "[category]") {
    CHECK(smql::model::categoryPattern("Trash Bin%") == "trash-bin%");
    CHECK(smql::model::categoryPattern("wall  plug") == "wall-plug");
    CHECK(smql::model::categoryPattern("%Plant_Stand") == "%plant_stand");
    CHECK(smql::model::categoryPattern("Chairs") == "chairs");
}

TEST_CASE("a category in words: its hyphens and underscores spaces", "[category]") {
    CHECK(categoryWords("sports-ball") == "sports ball");
    CHECK(categoryWords("sports_ball") == "sports ball");
    CHECK(categoryWords("chair") == "chair");
    CHECK(categoryWords(categoryName("Trash Bins")) == "trash bin");
}
