// The exchanges of ContactEngine::share_slots() (contact_engine.hpp, slot_sharing.hpp): each
// process packs the results of the slots it owns, one row per slot whose row is not all zero
// bits (a slot that touches nothing and released nothing sends nothing), the rows of every
// process are gathered, and each process writes the others' rows into its per-slot arrays.
// Rows carry the values bit for bit, so that the assembly and the sums that follow, over all
// slots in slot order, are the one-process ones.
#include <bit>
#include <cstdint>

#include "contact/contact_engine.hpp"

namespace xpl::contact {

namespace {

constexpr int TOUCH_WIDTH = 13;
/// share_springs(): two touches, three depths, the event face, two counted stiffnesses, and
/// whether the slot's interference ramps (so that a slot touching nothing sends its row).
constexpr int SPRING_WIDTH = 2 * TOUCH_WIDTH + 7;
/// share_forces(): two slave forces, two normal forces, two dissipations, the stored energy,
/// the ramp's work, the status, two user stiffnesses and their laws, two friction forces and
/// the contact normal.
constexpr int FORCE_WIDTH = 26;

/// An index as a row value: NO_INDEX is 0.
Real index_value(Index i) {
  return static_cast<Real>(i + 1);
}
Index value_index(Real v) {
  return static_cast<Index>(v) - 1;
}

void put_touch(const SlaveTouch& t, Real* row) {
  row[0] = index_value(t.face);
  row[1] = index_value(t.pair);
  row[2] = t.weight;
  row[3] = t.gap;
  for (int d = 0; d < 3; ++d) row[4 + d] = t.normal[d];
  for (int a = 0; a < 4; ++a) row[7 + a] = t.shape[a];
  row[11] = t.xi;
  row[12] = t.eta;
}

SlaveTouch get_touch(const Real* row) {
  SlaveTouch t;
  t.face = value_index(row[0]);
  if (t.face == NO_INDEX) return t;
  t.pair = value_index(row[1]);
  t.weight = row[2];
  t.gap = row[3];
  for (int d = 0; d < 3; ++d) t.normal[d] = row[4 + d];
  for (int a = 0; a < 4; ++a) t.shape[a] = row[7 + a];
  t.xi = row[11];
  t.eta = row[12];
  return t;
}

void put_vector(const Vec3& v, Real* row) {
  for (int d = 0; d < 3; ++d) row[d] = v[d];
}

Vec3 get_vector(const Real* row) {
  return Vec3(row[0], row[1], row[2]);
}

/// Appends slot s and its row to `out` unless every value of the row is +0; whether it did.
bool append_row(Index s, const Real* row, int width, std::vector<Real>& out) {
  bool any = false;
  for (int k = 0; k < width && !any; ++k) any = std::bit_cast<std::uint64_t>(row[k]) != 0;
  if (!any) return false;
  out.push_back(static_cast<Real>(s));
  out.insert(out.end(), row, row + width);
  return true;
}

/// Calls take(s, zeros) for every slot of `received` (the last exchange's, listed anew by
/// take_rows()).
template <class Take>
void reset_rows(int width, std::vector<Index>& received, Take take) {
  const std::vector<Real> zeros(static_cast<std::size_t>(width), 0.0);
  for (const Index s : received) take(s, zeros.data());
  received.clear();
}

/// Calls take(s, row) for every row of [first, last) (slot, then `width` values) of a slot
/// `owned` does not mark, and lists it in `received`.
template <class Take>
void take_rows(const Real* first, const Real* last, int width, const std::vector<char>& owned,
               std::vector<Index>& received, Take take) {
  for (const Real* row = first; row < last; row += 1 + width) {
    const auto s = static_cast<Index>(row[0]);
    if (owned[s] != 0) continue;
    take(s, row + 1);
    received.push_back(s);
  }
}

}  // namespace

void ContactEngine::share_active_slots() {
  std::vector<Real> mine;
  for (Index s = 0; s < static_cast<Index>(m_active_slot.size()); ++s)
    if (m_owned[s] != 0 && m_active_slot[s] != 0) mine.push_back(static_cast<Real>(s));
  std::vector<int> counts;
  for (const Real s : m_sharing->gather(mine, counts, false))
    m_active_slot[static_cast<std::size_t>(s)] = 1;
}

void ContactEngine::share_slots(std::vector<int> slot_process, int process, SlotSharing* sharing) {
  m_slot_process = std::move(slot_process);
  m_process = process;
  m_received_velocities = 0.0;
  m_owned.assign(m_slot_process.size(), 0);
  for (std::size_t s = 0; s < m_slot_process.size(); ++s)
    m_owned[s] = m_slot_process[s] == process ? 1 : 0;
  m_sharing = sharing;
  m_visit_all = true;
  // Whatever the whole passes before left in the other processes' slots is reset at the
  // first exchanges.
  m_received_springs.clear();
  if (m_sharing != nullptr)
    for (Index s = 0; s < m_domain.slaves().size(); ++s)
      if (m_owned[s] == 0) m_received_springs.push_back(s);
  m_received_forces = m_received_springs;
  m_work_velocity.clear();
  if (m_sharing != nullptr) m_work_velocity.assign(3 * m_slot_process.size(), 0.0);
}

void ContactEngine::share_springs() {
  std::vector<Real> mine;
  m_sent.clear();
  Real row[SPRING_WIDTH];
  const bool ramps = !m_interference.empty();
  for (Index s = 0; s < m_domain.slaves().size(); ++s) {
    if (m_owned[s] == 0) continue;
    // Most slots touch nothing: their row would be zero (no touch: no counted spring).
    if (m_touch[s].face == NO_INDEX && m_second_touch[s].face == NO_INDEX &&
        !(m_lost_depth[s] != 0.0 || m_passed_depth[s] != 0.0 || m_behind_depth[s] != 0.0) &&
        !(ramps && m_interference[s].amount > 0.0) && m_event_face[s] == NO_INDEX)
      continue;
    put_touch(m_touch[s], row);
    put_touch(m_second_touch[s], row + TOUCH_WIDTH);
    Real* r = row + 2 * TOUCH_WIDTH;
    r[0] = m_lost_depth[s];
    r[1] = m_passed_depth[s];
    r[2] = m_behind_depth[s];
    r[3] = index_value(m_event_face[s]);
    // The default springs cap_default_springs() counts in its sums (their stiffness).
    for (int side = 0; side < 2; ++side) {
      const Spring& spring = m_spring[2 * s + side];
      const bool counted = spring.k > 0.0 && spring.acts && !(spring.law.pressure_slope > 0.0);
      r[4 + side] = counted ? spring.k : 0.0;
    }
    r[6] = ramps && m_interference[s].amount > 0.0 ? 1.0 : 0.0;
    if (append_row(s, row, SPRING_WIDTH, mine)) m_sent.push_back(s);
  }
  const std::vector<Real> all = m_sharing->gather(mine, m_counts, false);
  const auto take = [&](Index s, const Real* row) {
    m_touch[s] = get_touch(row);
    m_second_touch[s] = get_touch(row + TOUCH_WIDTH);
    const Real* r = row + 2 * TOUCH_WIDTH;
    m_lost_depth[s] = r[0];
    m_passed_depth[s] = r[1];
    m_behind_depth[s] = r[2];
    m_event_face[s] = value_index(r[3]);
    for (int side = 0; side < 2; ++side) {
      Spring& spring = m_spring[2 * s + side];
      spring = Spring{};
      spring.k = r[4 + side];
      spring.acts = spring.k > 0.0;
    }
  };
  reset_rows(SPRING_WIDTH, m_received_springs, take);
  take_rows(all.data(), all.data() + all.size(), SPRING_WIDTH, m_owned, m_received_springs, take);
}

void ContactEngine::share_forces(const NodalVectors& velocity_half) {
  std::vector<Real> mine;
  Real row[FORCE_WIDTH];
  const bool ramps = !m_interference.empty();
  // The slots share_springs() sent: a slot whose springs row was zero touches nothing and
  // ramps nothing, so its forces row is zero too; each process's count is then known.
  for (const Index s : m_sent) {
    const bool first = m_touch[s].face != NO_INDEX, second = m_second_touch[s].face != NO_INDEX;
    for (int d = 0; d < 3; ++d) {
      row[d] = m_slave_force[3 * s + d];
      row[3 + d] = m_second_force[3 * s + d];
    }
    row[6] = m_normal_force[s];
    row[7] = second ? m_second_normal_force[s] : 0.0;  // read only with a second touch
    row[8] = m_dissipation[s];
    row[9] = m_second_dissipation[s];
    row[10] = m_stored[s];
    row[11] = ramps ? m_ramp_work[s] : 0.0;
    row[12] = static_cast<Real>(static_cast<int>(m_output_status[s]));
    for (int side = 0; side < 2; ++side) {
      const bool user = m_user_stiffness && m_user_k[2 * s + side] > 0.0;
      row[13 + side] = user ? m_user_k[2 * s + side] : 0.0;
      row[15 + side] = user ? index_value(m_user_law[2 * s + side]) : 0.0;
    }
    put_vector(m_constraints[s].tangential_force, row + 17);
    put_vector(m_second[s].tangential_force, row + 20);
    // The contact normal of a touching slot (a point node's output direction).
    put_vector(first ? m_constraints[s].normal : Vec3::Zero(), row + 23);
    mine.push_back(static_cast<Real>(s));
    mine.insert(mine.end(), row, row + FORCE_WIDTH);
  }
  // Then the velocity of the node of each own slot that may carry a force (mark_force_slots),
  // in slot order: the work terms every process sums over all slots.
  const auto n_processes = m_counts.size();
  std::vector<int> force_rows(n_processes, 0), velocities(n_processes, 0);
  for (std::size_t p = 0; p < n_processes; ++p)
    force_rows[p] = m_counts[p] / (1 + SPRING_WIDTH) * (1 + FORCE_WIDTH);
  mark_force_slots();
  const std::vector<Index>& nodes = m_domain.slaves().nodes();
  for (Index s = 0; s < static_cast<Index>(m_force_slot.size()); ++s) {
    if (m_force_slot[s] == 0) continue;
    velocities[m_slot_process[s]] += 3;
    if (m_owned[s] == 0) continue;
    for (int d = 0; d < 3; ++d) {
      m_work_velocity[3 * s + d] = velocity_half(nodes[s], d);
      mine.push_back(velocity_half(nodes[s], d));
    }
  }
  for (std::size_t p = 0; p < n_processes; ++p) m_counts[p] = force_rows[p] + velocities[p];
  const std::vector<Real> all = m_sharing->gather(mine, m_counts, true);
  const auto take = [&](Index s, const Real* r) {
    for (int d = 0; d < 3; ++d) {
      m_slave_force[3 * s + d] = r[d];
      m_second_force[3 * s + d] = r[3 + d];
    }
    m_normal_force[s] = r[6];
    m_second_normal_force[s] = r[7];
    m_dissipation[s] = r[8];
    m_second_dissipation[s] = r[9];
    m_stored[s] = r[10];
    if (ramps) m_ramp_work[s] = r[11];
    m_output_status[s] = static_cast<OutputStatus>(static_cast<int>(r[12]));
    if (m_user_stiffness)
      for (int side = 0; side < 2; ++side) {
        m_user_k[2 * s + side] = r[13 + side];
        m_user_law[2 * s + side] = value_index(r[15 + side]);
      }
    m_constraints[s].tangential_force = get_vector(r + 17);
    m_second[s].tangential_force = get_vector(r + 20);
    m_constraints[s].normal = get_vector(r + 23);
  };
  reset_rows(FORCE_WIDTH, m_received_forces, take);
  // Each process's block: its force rows, then its velocities in slot order (one cursor each).
  std::vector<const Real*> velocity_at(n_processes);
  const Real* block = all.data();
  for (std::size_t p = 0; p < n_processes; ++p) {
    take_rows(block, block + force_rows[p], FORCE_WIDTH, m_owned, m_received_forces, take);
    velocity_at[p] = block + force_rows[p];
    if (static_cast<int>(p) != m_process) m_received_velocities += velocities[p];
    block += m_counts[p];
  }
  for (Index s = 0; s < static_cast<Index>(m_force_slot.size()); ++s) {
    if (m_force_slot[s] == 0) continue;
    const Real*& v = velocity_at[m_slot_process[s]];
    for (int d = 0; d < 3; ++d) m_work_velocity[3 * s + d] = *v++;
  }
}

void ContactEngine::mark_force_slots() {
  // A node carries a contact force as a touching slave node or as a corner of a touched face
  // (every process holds every slot's touches after share_springs()), or carried one at the
  // last assembly (the previous force of the work term).
  const SlaveNodes& slaves = m_domain.slaves();
  const std::vector<ContactFace>& faces = m_domain.faces();
  m_force_slot.assign(static_cast<std::size_t>(slaves.size()), 0);
  for (Index s = 0; s < slaves.size(); ++s) {
    if (m_assembly.has_force(s)) m_force_slot[s] = 1;
    for (const SlaveTouch* t : {&m_touch[s], &m_second_touch[s]}) {
      if (t->face == NO_INDEX) continue;
      m_force_slot[s] = 1;
      for (const Index a : faces[t->face].nodes) m_force_slot[slaves.slot(a)] = 1;
    }
  }
}

}  // namespace xpl::contact
