// furnish_apartment(): the furniture rules per room type (docs/apartments.md, "Furniture
// rules"), then doors and windows in the plan's openings (apartment_fittings.cpp).
#include <functional>
#include <map>

#include "generator/apartment/apartment_placer.h"
#include "generator/apartment/apartment_roles.h"
#include "generator/apartment/apartment_steps.h"

namespace phyir::scenes {

void fit_openings(const ApartmentPlan& plan, const AssetLibrary& library, std::vector<PlacedAsset>& items, Pcg32& rng,
                  std::vector<std::string>& missing);

namespace {

constexpr int kCandidatesTried = 3;  // entries tried per role before giving up on it

class Furnisher {
 public:
  Furnisher(const AssetLibrary& library, RoomPlacer& placer, Pcg32& rng, std::vector<std::string>& missing)
      : library_(library), placer_(placer), rng_(rng), missing_(missing) {}

  // Tries up to kCandidatesTried entries of `role` with `move`; the piece's index or -1.
  int place(const std::string& role, const std::function<int(const AssetEntry*, const std::string&)>& move) {
    const std::vector<const AssetEntry*>& candidates = candidates_of(role);
    if (candidates.empty()) {
      missing_.push_back(role);
      return -1;
    }
    for (int k = 0; k < kCandidatesTried; ++k) {
      const int index = move(pick(candidates, rng_), role);
      if (index >= 0) return index;
    }
    return -1;
  }
  int against_wall(const std::string& role, int wall = -1) {
    return place(role, [&](const AssetEntry* e, const std::string& r) { return placer_.against_wall(e, r, wall); });
  }
  int in_corner(const std::string& role) {
    return place(role, [&](const AssetEntry* e, const std::string& r) { return placer_.in_corner(e, r); });
  }
  int on_top(int host, const std::string& role) {
    return place(role, [&](const AssetEntry* e, const std::string& r) { return placer_.on_top(host, e, r); });
  }
  int on_ceiling(const std::string& role) {
    return place(role, [&](const AssetEntry* e, const std::string& r) { return placer_.on_ceiling(e, r); });
  }
  int in_front_of(int other, const std::string& role, float gap) {
    return place(role, [&](const AssetEntry* e, const std::string& r) { return placer_.in_front_of(other, e, r, gap); });
  }
  int in_middle(const std::string& role) {
    return place(role, [&](const AssetEntry* e, const std::string& r) { return placer_.in_middle(e, r); });
  }
  // A set of one kind: every piece the same model, as in a real room.
  int beside(int bed, const std::string& role) { return placer_.beside(bed, one_model(role), role); }
  int around(int table, const std::string& role, int most) {
    return placer_.around(table, one_model(role), role, most);
  }
  void decorate(int host, int most) {
    for (int k = 0; k < most && host >= 0; ++k) on_top(host, "decor");
  }
  RoomPlacer& placer() { return placer_; }
  Pcg32& rng() { return rng_; }

 private:
  // One entry of the role, or nullptr (recorded as missing) when the library has none.
  const AssetEntry* one_model(const std::string& role) {
    const AssetEntry* e = pick(candidates_of(role), rng_);
    if (!e) missing_.push_back(role);
    return e;
  }

  const std::vector<const AssetEntry*>& candidates_of(const std::string& role) {
    auto it = cache_.find(role);
    if (it == cache_.end()) it = cache_.emplace(role, role_candidates(library_, role_spec(role))).first;
    return it->second;
  }

  const AssetLibrary& library_;
  RoomPlacer& placer_;
  Pcg32& rng_;
  std::vector<std::string>& missing_;
  std::map<std::string, std::vector<const AssetEntry*>> cache_;
};

void dining_set(Furnisher& f, int chairs) {
  const int table = f.in_middle("dining_table");
  if (table < 0) return;
  f.around(table, "dining_chair", chairs);
  f.decorate(table, 1);
}

void living_room(Furnisher& f, bool has_kitchen) {
  const int sofa = f.against_wall("sofa");
  if (sofa >= 0) f.decorate(f.in_front_of(sofa, "coffee_table", f.rng().uniform(0.35f, 0.5f)), 1);
  const int tv = f.against_wall("tv_stand", sofa >= 0 ? (f.placer().wall_of(sofa) + 2) % 4 : -1);
  f.decorate(tv, 1);
  for (int k = int(f.rng().below(3)); k > 0; --k) f.against_wall("armchair");
  for (int k = 1 + int(f.rng().below(2)); k > 0; --k) f.decorate(f.against_wall("bookcase"), 2);
  for (int k = 1 + int(f.rng().below(2)); k > 0; --k) f.in_corner("plant");
  f.in_corner("floor_lamp");
  if (!has_kitchen || f.rng().chance(0.4f)) dining_set(f, 4);
}

void kitchen(Furnisher& f) {
  // The units in a run along one wall, the upper cabinets above it.
  const int first = f.against_wall("fridge");
  const int wall = first >= 0 ? f.placer().wall_of(first) : -1;
  for (const char* role : {"stove", "sink_unit", "lower_cabinet", "lower_cabinet"}) {
    const int unit = f.against_wall(role, wall);
    if (unit >= 0 && f.rng().chance(0.7f)) f.on_top(unit, "kitchen_small");
  }
  for (int k = 0; k < 2; ++k) f.against_wall("upper_cabinet", wall);
  if (f.placer().floor().area() > 8.0f) dining_set(f, 2 + int(f.rng().below(3)));
  f.in_corner("plant");
}

void bedroom(Furnisher& f) {
  const int bed = f.against_wall("bed");
  const int before = f.placer().piece_count();
  if (bed >= 0) f.beside(bed, "bedside_table");
  // A lamp on each bedside table just placed.
  for (int piece = before, end = f.placer().piece_count(); piece < end; ++piece) f.on_top(piece, "table_lamp");
  f.against_wall("wardrobe");
  if (f.rng().chance(0.5f)) f.decorate(f.against_wall("bookcase"), 2);
  if (f.rng().chance(0.5f)) f.in_corner("plant");
}

void bathroom(Furnisher& f) {
  f.against_wall("bath");
  f.against_wall("toilet");
  const int basin = f.against_wall("washbasin");
  if (basin >= 0) f.on_top(basin, "bathroom_small");
  if (f.rng().chance(0.6f)) f.against_wall("towel_rack");
}

void corridor(Furnisher& f) {
  if (f.rng().chance(0.6f)) f.decorate(f.against_wall("bookcase"), 1);
  if (f.rng().chance(0.6f)) f.in_corner("plant");
}

bool is_lamp_role(const std::string& role) {
  return role == "floor_lamp" || role == "table_lamp" || role == "ceiling_light";
}

}  // namespace

ApartmentFurnishing furnish_apartment(const ApartmentPlan& plan, const AssetLibrary& library, AssetModelCache& models,
                                      ApartmentLighting lighting) {
  ApartmentFurnishing out;
  Pcg32 rng = apartment_rng(plan.seed, plan.index, ApartmentStream::Furniture);
  bool has_kitchen = false;
  for (const ApartmentRoom& r : plan.rooms) has_kitchen = has_kitchen || r.type == RoomType::Kitchen;
  for (size_t r = 0; r < plan.rooms.size(); ++r) {
    RoomPlacer placer(plan, int(r), out.items, models, rng);
    Furnisher f(library, placer, rng, out.unfurnished_roles);
    f.on_ceiling("ceiling_light");  // first, while the middle of the ceiling is free
    switch (plan.rooms[r].type) {
      case RoomType::LivingRoom: living_room(f, has_kitchen); break;
      case RoomType::Kitchen: kitchen(f); break;
      case RoomType::Bedroom: bedroom(f); break;
      case RoomType::Bathroom: bathroom(f); break;
      case RoomType::Corridor: corridor(f); break;
    }
  }
  for (PlacedAsset& p : out.items) p.lamp_on = lighting == ApartmentLighting::Night && is_lamp_role(p.role);
  Pcg32 fittings = apartment_rng(plan.seed, plan.index, ApartmentStream::Openings);
  fit_openings(plan, library, out.items, fittings, out.unfurnished_roles);
  return out;
}

}  // namespace phyir::scenes
