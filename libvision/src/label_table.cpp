#include <drape/vision/label_table.hpp>

#include <drape/core/errors.hpp>

#include <algorithm>

namespace drape::vision {

namespace {

// labels.txt of ../shared/data/photos (Fashionista clothings.mat row order).
const char* const kFashionistaNames[] = {
    "null",     "accessories", "bag",      "belt",     "blazer",    "blouse",   "bodysuit",
    "boots",    "bra",         "bracelet", "cape",     "cardigan",  "clogs",    "coat",
    "dress",    "earrings",    "flats",    "glasses",  "gloves",    "hair",     "hat",
    "heels",    "hoodie",      "intimate", "jacket",   "jeans",     "jumper",   "leggings",
    "loafers",  "necklace",    "panties",  "pants",    "pumps",     "purse",    "ring",
    "romper",   "sandals",     "scarf",    "shirt",    "shoes",     "shorts",   "skin",
    "skirt",    "sneakers",    "socks",    "stockings", "suit",     "sunglasses", "sweater",
    "sweatshirt", "swimwear",  "t-shirt",  "tie",      "tights",    "top",      "vest",
    "wallet",   "watch",       "wedges"};

bool in(std::string_view name, std::initializer_list<std::string_view> list) {
    return std::find(list.begin(), list.end(), name) != list.end();
}

}  // namespace

LabelRole role_from_name(std::string_view n) {
    if (n == "null" || n == "background") return LabelRole::background;
    if (n == "skin") return LabelRole::skin;
    if (n == "hair") return LabelRole::hair;
    if (in(n, {"blouse", "bodysuit", "shirt", "t-shirt", "top", "sweater", "sweatshirt",
               "hoodie", "jumper"}))
        return LabelRole::upper_garment;
    if (in(n, {"skirt", "pants", "jeans", "shorts", "leggings"})) return LabelRole::lower_garment;
    if (in(n, {"dress", "romper"})) return LabelRole::full_garment;
    if (in(n, {"accessories", "bag", "belt", "purse", "wallet", "scarf", "blazer", "cape",
               "cardigan", "coat", "jacket", "vest", "suit", "tie", "necklace", "bracelet",
               "watch", "gloves"}))
        return LabelRole::occluder;
    return LabelRole::other;
}

const LabelTable& LabelTable::fashionista() {
    static const LabelTable table = [] {
        std::vector<std::pair<int, std::string>> rows;
        int id = 0;
        for (const char* n : kFashionistaNames) rows.emplace_back(id++, n);
        return from_names(rows);
    }();
    return table;
}

LabelTable LabelTable::from_names(const std::vector<std::pair<int, std::string>>& rows) {
    LabelTable t;
    t.roles_.fill(LabelRole::other);
    for (const auto& [id, name] : rows) {
        require(id >= 0 && id < kUnmarked, "label table: id ", id, " ('", name,
                "') is outside 0..254 (255 marks unmarked stroke pixels)");
        require(!t.present_[static_cast<size_t>(id)], "label table: id ", id,
                " appears twice ('", t.names_[static_cast<size_t>(id)], "', '", name, "')");
        t.present_[static_cast<size_t>(id)] = true;
        t.names_[static_cast<size_t>(id)] = name;
        t.roles_[static_cast<size_t>(id)] = role_from_name(name);
    }
    return t;
}

bool LabelTable::contains(int id) const {
    return id >= 0 && id < kUnmarked && present_[static_cast<size_t>(id)];
}

const std::string& LabelTable::name(int id) const {
    require(contains(id), "label id ", id, " is not in the label table");
    return names_[static_cast<size_t>(id)];
}

LabelRole LabelTable::role(int id) const {
    return contains(id) ? roles_[static_cast<size_t>(id)] : LabelRole::other;
}

int LabelTable::id(std::string_view n) const {
    for (int i = 0; i < kUnmarked; ++i)
        if (present_[static_cast<size_t>(i)] && names_[static_cast<size_t>(i)] == n) return i;
    return -1;
}

std::vector<int> LabelTable::ids_with_role(LabelRole r) const {
    std::vector<int> out;
    for (int i = 0; i < kUnmarked; ++i)
        if (present_[static_cast<size_t>(i)] && roles_[static_cast<size_t>(i)] == r)
            out.push_back(i);
    return out;
}

}  // namespace drape::vision
