!> What a dynamic run records, beside the step: the history rows (one every
!> OUTPUT EVERY= steps), the snapshots (t = 0, the FIELDS= times, the end,
!> and the kept states at maximum deformation and pressure), the stored
!> strain energy and the summary keys of the end state.
module visco2d_dynamic_record
  use visco2d_kinds, only: dp, whole_body_factor, energy_basis, kinematics_large
  use visco2d_strings, only: integer_text, message_real, short_real
  use visco2d_deck, only: deck_t, total_steps, stop_name
  use visco2d_element, only: gauss_count
  use visco2d_assembly, only: node_dof, nodal_field
  use visco2d_viscoelastic, only: element_terms, stored_energy_density
  use visco2d_stress_recovery, only: node_corners, corner_stress
  use visco2d_field_summary, only: put_field_summary, put_probe_summary, set_snapshot_stress
  use visco2d_record, only: record_t, snapshot_t, record_put, record_put_real, record_put_integer, history_define, &
                            history_append, record_add_snapshot, record_insert_snapshot, record_warn
  use visco2d_impact, only: impact_t, impact_columns, impact_row, sensor_acceleration
  use visco2d_operators, only: operators_t
  use visco2d_dynamic_state, only: dynamic_state_t
  use visco2d_energy_balance, only: energy_balance_t
  implicit none
  private

  public :: kept_state_t, dynamic_log_t, log_create, log_row, log_snapshot, log_field_times, keep_state, &
            insert_kept_snapshot, stored_energy, centre_of_mass, put_end_summary, warn_unwritten_fields

  !> The (corner, element) pairs at a probe node (node_corners).
  type :: corners_t
    integer, allocatable :: pairs(:, :)
  end type corners_t

  !> The state at a running maximum, kept as plain copies (no conversion per
  !> step): it becomes a snapshot once, at the end of the run.
  type :: kept_state_t
    logical :: kept = .false.
    integer :: step = 0
    real(dp) :: time = 0.0_dp
    real(dp), allocatable :: u(:), v(:), a(:), stress(:, :, :), strain(:, :, :)
  end type kept_state_t

  !> The recording state: the history row, probe corners, the next FIELDS=
  !> time, the body's mass for the centre of mass, the energy basis factor.
  type :: dynamic_log_t
    real(dp), allocatable :: row(:)
    type(corners_t), allocatable :: probe_corners(:)
    integer :: width = 6                  !< digits of the snapshot names
    integer :: next_field = 1
    logical :: contact_on = .false.
    real(dp), allocatable :: mass_z(:)    !< lumped masses of the z equations
    real(dp), allocatable :: node_mass(:) !< (nnode, node order) the same, the weights of a sensor (PROBE ... RADIUS=)
    real(dp) :: body_mass = 0.0_dp        !< per radian in axisymmetry
    real(dp) :: basis_factor = 1.0_dp     !< whole_body_factor: solver integrals to the reported energy_basis
  end type dynamic_log_t

contains

  !> The log of a run and its history columns.
  subroutine log_create(deck, mass, contact_on, record, log)
    type(deck_t), intent(in) :: deck
    real(dp), intent(in) :: mass(:)
    logical, intent(in) :: contact_on
    type(record_t), intent(inout) :: record
    type(dynamic_log_t), intent(out) :: log
    character(len=48), allocatable :: columns(:)
    integer :: p, k
    character(len=8), parameter :: probe_columns(10) = ['ur_m    ', 'uz_m    ', 'vr_m_s  ', 'vz_m_s  ', &
      'ar_m_s2 ', 'az_m_s2 ', 'sr_Pa   ', 'sz_Pa   ', 'st_Pa   ', 'trz_Pa  ']
    log%contact_on = contact_on
    log%mass_z = mass(2::2)
    associate (nodal_mass => nodal_field(deck%mesh, mass))
    log%node_mass = nodal_mass(2, :)
    end associate
    log%body_mass = sum(mass(2::2))
    log%basis_factor = whole_body_factor(deck%settings%geometry)
    log%width = max(6, len(integer_text(total_steps(deck))))
    allocate(log%probe_corners(size(deck%probes)))
    do k = 1, size(deck%probes)
      log%probe_corners(k)%pairs = node_corners(deck%mesh, deck%probes(k)%node)
    end do
    columns = [character(len=48) :: 'step', 't_s', 'max_displacement_m', 'uz_cm_m', 'vz_cm_m_s', &
               'az_cm_m_s2', 'kinetic_J', 'strain_J', 'dissipated_J', 'external_work_J', 'gravity_work_J', &
               'balance_error_J', 'reaction_r_N', 'reaction_z_N']
    if (contact_on) columns = [character(len=48) :: columns, impact_columns(deck%pad%line > 0, deck%body%line > 0), &
                               'contact_loss_J']
    do p = 1, size(deck%probes)
      do k = 1, size(probe_columns)
        columns = [character(len=48) :: columns, deck%probes(p)%name//'_'//trim(probe_columns(k))]
      end do
      if (deck%probes(p)%radius > 0.0_dp) columns = [character(len=48) :: columns, &
        deck%probes(p)%name//'_sensor_ar_m_s2', deck%probes(p)%name//'_sensor_az_m_s2']
    end do
    call history_define(record, columns, total_steps(deck)/deck%output%every + 2)
    allocate(log%row(size(columns)))
  end subroutine log_create

  !> Mass-weighted mean of the z components of a nodal vector (the centre of mass).
  real(dp) function centre_of_mass(log, vector)
    type(dynamic_log_t), intent(in) :: log
    real(dp), intent(in) :: vector(:)
    centre_of_mass = dot_product(log%mass_z, vector(2::2))/log%body_mass
  end function centre_of_mass

  !> One history row (the columns of log_create). t_ms and alpha_mm are
  !> filled in by impact_summary, once first contact is known.
  subroutine log_row(log, deck, record, step, state, book, stored, impact)
    type(dynamic_log_t), intent(inout) :: log
    type(deck_t), intent(in) :: deck
    type(record_t), intent(inout) :: record
    integer, intent(in) :: step
    type(dynamic_state_t), intent(in) :: state
    type(energy_balance_t), intent(in) :: book
    real(dp), intent(in) :: stored                  !< strain energy stored in the springs
    type(impact_t), intent(in) :: impact
    integer :: p, node, first, columns_impact
    real(dp) :: largest
    associate (u => state%u, row => log%row)
    largest = 0.0_dp
    do node = 1, deck%mesh%nnode
      largest = max(largest, hypot(u(node_dof(deck%mesh, node, 1)), u(node_dof(deck%mesh, node, 2))))
    end do
    row(1:14) = [real(step, dp), state%t, largest, centre_of_mass(log, u), centre_of_mass(log, state%v), &
                 centre_of_mass(log, state%a), log%basis_factor*[book%kinetic, stored, book%internal_work - stored, &
                 book%load_work + book%support_work, book%gravity_work, book%balance, sum(state%reaction(1::2)), &
                 sum(state%reaction(2::2))]]
    first = 15
    if (log%contact_on) then
      columns_impact = size(impact_columns(impact%pad, impact%second))
      row(first:first + columns_impact - 1) = impact_row(impact)
      row(first + columns_impact) = log%basis_factor*book%contact_loss
      first = first + columns_impact + 1
    end if
    do p = 1, size(deck%probes)
      node = deck%probes(p)%node
      associate (r => node_dof(deck%mesh, node, 1), z => node_dof(deck%mesh, node, 2))
      row(first:first + 9) = [u(r), u(z), state%v(r), state%v(z), state%a(r), state%a(z), &
                              corner_stress(state%stress, log%probe_corners(p)%pairs)]
      end associate
      first = first + 10
      if (deck%probes(p)%radius <= 0.0_dp) cycle
      row(first:first + 1) = sensor_acceleration(deck, deck%probes(p), log%node_mass, state%a)
      first = first + 2
    end do
    call history_append(record, row)
    end associate
  end subroutine log_row

  !> After a step at time t: a snapshot at each FIELDS= time reached (then
  !> skipped past every requested time at or before t).
  subroutine log_field_times(log, deck, record, step, state, snapshot)
    type(dynamic_log_t), intent(inout) :: log
    type(deck_t), intent(in) :: deck
    type(record_t), intent(inout) :: record
    integer, intent(in) :: step
    type(dynamic_state_t), intent(in) :: state
    logical, intent(in) :: snapshot                 !< .false.: only skip (t = 0)
    associate (times => deck%output%field_times)
    if (log%next_field > size(times)) return
    if (state%t < times(log%next_field)*(1.0_dp - 1.0e-12_dp)) return
    if (snapshot) call log_snapshot(log, deck, record, 't = '//short_real(times(log%next_field))//' s requested', &
                                    step, state)
    do while (log%next_field <= size(times))
      if (times(log%next_field)*(1.0_dp - 1.0e-12_dp) > state%t) exit
      log%next_field = log%next_field + 1
    end do
    end associate
  end subroutine log_field_times

  !> After the step loop at time t: a run stopped before TEND (STOP
  !> AT=MAXDEFORMATION or SEPARATION) writes no snapshot at the FIELDS= times
  !> after t; a run-time warning at the OUTPUT card names them.
  subroutine warn_unwritten_fields(log, deck, record, t)
    type(dynamic_log_t), intent(in) :: log
    type(deck_t), intent(in) :: deck
    type(record_t), intent(inout) :: record
    real(dp), intent(in) :: t
    associate (times => deck%output%field_times)
    if (log%next_field > size(times)) return
    call record_warn(record, integer_text(size(times) - log%next_field + 1)//' FIELDS time(s) from '// &
      short_real(times(log%next_field))//' s on not written: the run stopped at t = '//message_real(t)//' s (STOP AT='// &
      stop_name(deck%stop_at)//') before them, so results.h5 has no snapshot there', &
      file=deck%cards%file, line=deck%output%line, card='OUTPUT')
    end associate
  end subroutine warn_unwritten_fields

  !> A snapshot of the state now, named after the step (or the label added
  !> to the last one when it is already kept at this time).
  subroutine log_snapshot(log, deck, record, label, step, state)
    type(dynamic_log_t), intent(in) :: log
    type(deck_t), intent(in) :: deck
    type(record_t), intent(inout) :: record
    character(*), intent(in) :: label
    integer, intent(in) :: step
    type(dynamic_state_t), intent(in) :: state
    type(snapshot_t) :: snapshot
    if (allocated(record%snapshots)) then
      if (size(record%snapshots) > 0) then
        associate (last => record%snapshots(size(record%snapshots)))
        if (last%time == state%t) then                                 ! already kept at this step
          last%label = last%label//'; '//label
          return
        end if
        end associate
      end if
    end if
    snapshot = fields_snapshot(log, deck, label, step, state%t, state%u, state%v, state%a, state%stress)
    call record_add_snapshot(record, snapshot)
  end subroutine log_snapshot

  !> A snapshot named after its step: nodal displacement, velocity,
  !> acceleration and the stresses (Gauss and recovered nodal values).
  function fields_snapshot(log, deck, label, at_step, time, u, v, a, stress) result(snapshot)
    type(dynamic_log_t), intent(in) :: log
    type(deck_t), intent(in) :: deck
    character(*), intent(in) :: label
    integer, intent(in) :: at_step
    real(dp), intent(in) :: time, u(:), v(:), a(:), stress(:, :, :)
    type(snapshot_t) :: snapshot
    character(len=16) :: digits
    write(digits, '(i0.'//integer_text(log%width)//')') at_step
    snapshot%name = 'step_'//trim(digits)
    snapshot%label = label
    snapshot%time = time
    snapshot%displacement = nodal_field(deck%mesh, u)
    snapshot%velocity = nodal_field(deck%mesh, v)
    snapshot%acceleration = nodal_field(deck%mesh, a)
    call set_snapshot_stress(deck%mesh, stress, snapshot)
  end function fields_snapshot

  !> Copy the state now (the arrays are allocated once, at the first copy).
  subroutine keep_state(kept, step, state)
    type(kept_state_t), intent(inout) :: kept
    integer, intent(in) :: step
    type(dynamic_state_t), intent(in) :: state
    kept%kept = .true.
    kept%step = step
    kept%time = state%t
    kept%u = state%u
    kept%v = state%v
    kept%a = state%a
    kept%stress = state%stress
    kept%strain = state%strain
  end subroutine keep_state

  !> A kept state as a snapshot (nodal fields and stresses), inserted in time order.
  subroutine insert_kept_snapshot(log, deck, record, kept, label)
    type(dynamic_log_t), intent(in) :: log
    type(deck_t), intent(in) :: deck
    type(record_t), intent(inout) :: record
    type(kept_state_t), intent(in) :: kept
    character(*), intent(in) :: label
    type(snapshot_t) :: snapshot
    if (.not. kept%kept) return
    snapshot = fields_snapshot(log, deck, label, kept%step, kept%time, kept%u, kept%v, kept%a, kept%stress)
    call record_insert_snapshot(record, snapshot)
  end subroutine insert_kept_snapshot

  !> Strain energy stored in the springs: per Gauss point
  !> K theta^2/2 + G_inf e:e + sum_m G_m C_m:C_m (C_m = the history of term m,
  !> whose spring carries s_m = 2 G_m C_m), times |J| r; with KINEMATICS
  !> LARGE the hyperelastic W of the state (visco2d_finite_assembly).
  real(dp) function stored_energy(deck, operators, state, memory) result(energy)
    type(deck_t), intent(in) :: deck
    type(operators_t), intent(in) :: operators
    type(dynamic_state_t), intent(in) :: state
    logical, intent(in) :: memory
    real(dp), parameter :: no_history(4, 0) = 0.0_dp
    real(dp) :: elastic(4)
    integer :: e, g, nterm, slot
    energy = state%strain_energy                    ! KINEMATICS LARGE: W, evaluated with the stresses
    if (deck%settings%kinematics == kinematics_large) return
    energy = 0.0_dp
    do e = 1, deck%mesh%nelem
      associate (material => deck%materials(deck%mesh%element_material(e)))
      nterm = 0
      if (memory) nterm = element_terms(state%history, e)
      do g = 1, gauss_count
        elastic = state%strain(:, g, e)                 ! less the plastic strain of a PLASTIC material
        if (allocated(state%plastic_strain)) elastic = elastic - state%plastic_strain(:, g, e)
        if (nterm == 0) then
          energy = energy + operators%weight(g, e)*stored_energy_density(material, elastic, no_history)
        else
          slot = state%history%first(e) + (g - 1)*nterm
          energy = energy + operators%weight(g, e)*stored_energy_density(material, elastic, &
                                                                         state%history%history(:, slot:slot + nterm - 1))
        end if
      end do
      end associate
    end do
  end function stored_energy

  !> The summary keys of the end state: centre of mass, energies on the
  !> energy_basis (the solver's per-radian integrals times 2 pi in
  !> axisymmetry: whole body; per metre of thickness in plane strain).
  subroutine put_end_summary(log, deck, record, state, book, stored, history_values)
    type(dynamic_log_t), intent(in) :: log
    type(deck_t), intent(in) :: deck
    type(record_t), intent(inout) :: record
    type(dynamic_state_t), intent(in) :: state
    type(energy_balance_t), intent(in) :: book
    real(dp), intent(in) :: stored
    integer, intent(in) :: history_values
    associate (f => log%basis_factor)
    call record_put_real(record, 'time_end_s', state%t)
    call record_put(record, 'energy_basis', energy_basis(deck%settings%geometry))
    call record_put_real(record, 'mass_kg', f*log%body_mass)
    call record_put_real(record, 'body_mass_kg', f*log%body_mass)
    call record_put_integer(record, 'history_values', history_values)
    call record_put_real(record, 'uz_cm_m', centre_of_mass(log, state%u))
    call record_put_real(record, 'vz_cm_m_s', centre_of_mass(log, state%v))
    call record_put_real(record, 'az_cm_m_s2', centre_of_mass(log, state%a))
    call record_put_real(record, 'kinetic_J', f*book%kinetic)
    call record_put_real(record, 'strain_energy_J', f*stored)
    call record_put_real(record, 'dissipated_J', f*(book%internal_work - stored))
    call record_put_real(record, 'external_work_J', f*(book%load_work + book%support_work))
    call record_put_real(record, 'gravity_work_J', f*book%gravity_work)
    call record_put_real(record, 'initial_kinetic_J', f*book%kinetic0)
    if (log%contact_on) call record_put_real(record, 'contact_loss_J', f*book%contact_loss)
    call put_sensor_summary(log, deck, record)
    call record_put_real(record, 'balance_error_J', f*book%balance)
    call record_put_real(record, 'balance_error_max_J', f*book%balance_max)
    call record_put_real(record, 'balance_error_max_rel', book%balance_max/max(book%input_max, tiny(1.0_dp)))
    end associate
  end subroutine put_end_summary

  !> What each sensor (PROBE ... RADIUS=) covers: its radius, its number of
  !> nodes and their mass (on the energy_basis: whole body in axisymmetry),
  !> and what it reads (probe_<name>_sensor_reads): the rigid-body
  !> acceleration of its region, which is not the body's F/M. At the centre
  !> of the Fig. 2 apple (10 mm, Delta t = 0.005 ms) it reads 45.9, 46.6 g
  !> at level 5 with Wilson-theta and Newmark (1.12, 1.13 x the centre of
  !> mass's 41.1 g), 2.6, 1.8 % below level 4, tending to about 1.11-1.13 x:
  !> the stress waves of the node-by-node arrests on the plate (under a
  !> smooth load without arrests it reads close to F/M; doc/verification.md).
  subroutine put_sensor_summary(log, deck, record)
    type(dynamic_log_t), intent(in) :: log
    type(deck_t), intent(in) :: deck
    type(record_t), intent(inout) :: record
    integer :: p
    do p = 1, size(deck%probes)
      associate (probe => deck%probes(p))
      if (probe%radius <= 0.0_dp) cycle
      call record_put_real(record, 'probe_'//probe%name//'_sensor_radius_m', probe%radius)
      call record_put_integer(record, 'probe_'//probe%name//'_sensor_nodes', size(probe%region))
      call record_put_real(record, 'probe_'//probe%name//'_sensor_mass_kg', &
                           log%basis_factor*sum(log%node_mass(probe%region)))
      call record_put(record, 'probe_'//probe%name//'_sensor_reads', 'the mean acceleration sum(m a)/sum(m) '// &
        'of the nodes within RADIUS (the rigid-body acceleration of that region), not the body''s F/M '// &
        '(accel_cm_max_g): on a plate it carries the stress waves of the node-by-node arrests, which '// &
        'shrink only slowly with the mesh level and DT (doc/outputs.md)')
      end associate
    end do
  end subroutine put_sensor_summary
end module visco2d_dynamic_record
