// A category's one canonical name. However a file, a detector or a person writes a kind of thing
// ("Trash_Can", "trash can", "trash-can", "trash cans"), it is one category, stored and looked up
// as categoryName() spells it: "trash-can". Every importer, ingest and every lookup (FIND, COUNT,
// the predicates' arguments, ASK, SIMILAR TO, SHOW CATEGORIES, the shell's .categories) goes
// through this one function; docs/language.md ("Categories") gives the rule.
#pragma once

#include <string>
#include <string_view>

namespace smql::model {

struct SceneData;

// The category of a thing the ingest found but could not name (a cluster of points, a name its box or its place
// did not fit, kept as `detected_as`).
inline constexpr std::string_view kUnnamedCategory = "object";

// The canonical form of a category: lower case (ASCII letters; other bytes as written); every run
// of spaces, tabs, hyphens and underscores one hyphen, none at either end; the last word singular
// (English endings, with a table of irregular plurals and of words that end in s but are singular
// or have no singular: "glass", "blinds"). Empty stays empty.
std::string categoryName(std::string_view written);

// A LIKE pattern over category names, folded as categoryName folds a name where a pattern can be:
// lower case, every run of spaces and hyphens one hyphen ('Trash Bin%' -> 'trash-bin%'); the
// wildcards (% and _, which matches a hyphen too) and plurals stay as written.
std::string categoryPattern(std::string_view pattern);

// A category as words say it: each hyphen or underscore a space ("sports-ball", "sports_ball" -> "sports ball").
std::string categoryWords(std::string_view category);

// Whether `written` is already in canonical form (categoryName(written) == written), without
// building a string in the common case.
bool isCategoryName(std::string_view written);

// The singular of one lower-case English word, by the same table ("shelves" -> shelf, "mice" ->
// mouse, "boxes" -> box, "blinds" -> blinds); a word that is not a plural is returned as it is.
std::string singularWord(std::string_view word);

// Every node of `scene` but the scene node (whose category is the scene's name) gets its
// canonical category.
void canonicaliseCategories(SceneData& scene);

}  // namespace smql::model
