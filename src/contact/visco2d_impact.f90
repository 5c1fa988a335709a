!> What an impact on the plate reports (the summary keys of doc/outputs.md), measured after
!> every step of a dynamic run with a PLATE: first contact (t = 0 of the
!> results), alpha = the approach of the centre of mass since then, the plate
!> force and the pressure at the pole, the contact radius, the centre's
!> acceleration and the sensors' (PROBE ... RADIUS=), their maxima, and the
!> stop criteria of the STOP card.
module visco2d_impact
  use visco2d_kinds, only: dp, pi, geometry_axisymmetric
  use visco2d_strings, only: short_real
  use visco2d_deck, only: deck_t, probe_t, stop_at_tend, stop_at_max_deformation, stop_at_separation, stop_name
  use visco2d_assembly, only: node_dof, nodal_field
  use visco2d_stress_recovery, only: node_corners, corner_stress
  use visco2d_element, only: element_strains, gauss_count
  use visco2d_assembly, only: gather
  use visco2d_material, only: stress_from_strain
  use visco2d_viscoelastic, only: step_coefficients_t, viscoelastic_state_t, element_terms, history_stress
  use visco2d_contact, only: contact_t, contact_count, contact_pressure, contact_force, contact_radius, &
                             nearest_free_node, pad_compression
  use visco2d_hertz, only: put_hertz_summary
  use visco2d_two_bodies, only: put_two_body_hertz
  use visco2d_record, only: record_t, record_put, record_put_real, record_put_integer, record_column, record_warn
  use visco2d_sorting, only: sorted_order
  implicit none
  private

  public :: impact_t, impact_start, impact_measure, impact_summary, impact_columns, impact_row, impact_surface_stress
  public :: sensor_acceleration

  !> One g, m/s^2, the unit of accel_center_g (the standard acceleration of gravity).
  real(dp), parameter :: g_unit = 9.80665_dp

  !> The running measures of an impact (SI units; times since first contact).
  type :: impact_t
    integer :: centre_node = 0                !< the node nearest the centre of mass
    real(dp) :: t_contact = -1.0_dp           !< s, deck time of first contact (< 0: none yet)
    real(dp) :: u_cm_contact = 0.0_dp, v_cm_contact = 0.0_dp  !< centre of mass at first contact
    logical :: stopped = .false.              !< the STOP criterion is met
    character(:), allocatable :: stop_reason
    logical :: paper_fired = .false.          !< the paper's criterion has fired (at t_paper)
    logical :: alpha_passed = .false.         !< alpha has passed its maximum
    real(dp) :: t_paper = -1.0_dp
    real(dp) :: t_separation = -1.0_dp, v_separation = 0.0_dp
    integer :: contact_nodes = 0, contact_nodes_max = 0
    real(dp) :: alpha = 0.0_dp, alpha_max = 0.0_dp, t_alpha_max = 0.0_dp
    !> alpha and time (since contact) at the step before the sampled maximum
    !> and at the step after it (the parabola through the three, at the end)
    real(dp) :: alpha_previous = 0.0_dp, t_previous = 0.0_dp
    real(dp) :: alpha_before = 0.0_dp, t_before = 0.0_dp, alpha_after = 0.0_dp, t_after = 0.0_dp
    logical :: have_before = .false., have_after = .false.
    real(dp) :: q = 0.0_dp, q_max = 0.0_dp, t_q_max = 0.0_dp
    real(dp) :: q_surface = 0.0_dp, q_surface_max = 0.0_dp, t_q_surface_max = 0.0_dp
    real(dp) :: q_surface_tau = 0.0_dp        !< -sigma_z at the pole at t + theta dt (impact_surface_stress)
    logical :: have_surface_tau = .false.     !< q_surface_tau is this step's
    real(dp) :: force = 0.0_dp, force_max = 0.0_dp, t_force_max = 0.0_dp
    real(dp) :: radius = 0.0_dp, radius_max = 0.0_dp
    real(dp) :: accel_centre = 0.0_dp, accel_max = -huge(1.0_dp), t_accel_max = 0.0_dp
    real(dp) :: accel_cm_max = -huge(1.0_dp)
    real(dp), allocatable :: mass_z(:)        !< (nnode, node order) lumped mass of each node's z equation (sensor weights)
    !> (probe) the sensor's a_z now and its largest value since contact, and when (PROBE ... RADIUS=)
    real(dp), allocatable :: sensor(:), sensor_max(:), t_sensor_max(:)
    real(dp), allocatable :: pressure(:)      !< (nnode) recovered contact pressure, Pa
    logical, allocatable :: ever_active(:)    !< (nnode) on the plate at some step
    !> (nnode) contact pressure (Pa) and deformed r (m) at the largest plate force and at the largest sampled alpha
    real(dp), allocatable :: pressure_at_force_max(:), r_at_force_max(:), pressure_at_alpha_max(:), r_at_alpha_max(:)
    !> (nnode) plate reaction in z on each contact node (0 off the plate), N, at the same two instants:
    !> whole ring (2 pi times the per-radian nodal reaction) in axisymmetry, per metre in plane strain,
    !> the basis of force_N, so that they sum to the plate force
    real(dp), allocatable :: reaction_at_force_max(:), reaction_at_alpha_max(:)
    integer, allocatable :: pole_corners(:, :) !< (corner, element) pairs at the pole (node_corners)
    logical :: pad = .false.                  !< on a PAD: alpha is the approach less the pad's compression
    real(dp) :: pad_compression = 0.0_dp, pad_compression_max = 0.0_dp, t_pad_compression_max = 0.0_dp
    !> the largest compressive -sigma_z at a Gauss point of the pad, Pa, and when
    real(dp) :: pad_stress = 0.0_dp, pad_stress_max = 0.0_dp, t_pad_stress_max = 0.0_dp
    !> A second BODY: alpha is the approach of the two centres of mass; its
    !> lumped masses (band order, 0 off it), total (per radian), centre of
    !> mass displacement and velocity now, at the step before, at first
    !> contact and at separation; the top pole of its surface.
    logical :: second = .false.
    real(dp), allocatable :: mass2(:)
    real(dp) :: body2_mass = 0.0_dp
    real(dp) :: u2 = 0.0_dp, v2 = 0.0_dp, u2_previous = 0.0_dp, v2_previous = 0.0_dp
    real(dp) :: u2_contact = 0.0_dp, v2_contact = 0.0_dp, v2_separation = 0.0_dp
    integer :: pole2 = 0
    !> each body's own deformation on the axis: u_z(pole 1) - u_z,cm1 and u_z,cm2 - u_z(pole 2)
    !> (both bodies translate rigidly before contact), m, and their maxima
    real(dp) :: deformation1 = 0.0_dp, deformation1_max = 0.0_dp, deformation2 = 0.0_dp, deformation2_max = 0.0_dp
  end type impact_t

contains

  !> The impact state at t = 0: the centre node (nearest the centre of mass;
  !> on the axis in axisymmetry) and the initial acceleration there.
  subroutine impact_start(deck, mass, a, impact, mass2, v)
    type(deck_t), intent(in) :: deck
    real(dp), intent(in) :: mass(:), a(:)   !< lumped mass and acceleration, band order
    type(impact_t), intent(out) :: impact
    !> with a second BODY: its lumped masses (band order, 0 off it) and the initial velocity
    real(dp), intent(in), optional :: mass2(:), v(:)
    real(dp) :: centre(2)
    integer :: node
    associate (nodal_mass => nodal_field(deck%mesh, mass))               ! (2, nnode), node order
    centre(2) = dot_product(nodal_mass(2, :), deck%mesh%xy(2, :))/sum(nodal_mass(2, :))
    centre(1) = dot_product(nodal_mass(1, :), deck%mesh%xy(1, :))/max(sum(nodal_mass(1, :)), tiny(1.0_dp))
    end associate
    if (deck%settings%geometry == geometry_axisymmetric) centre(1) = 0.0_dp
    impact%centre_node = 1
    do node = 2, deck%mesh%nnode
      if (norm2(deck%mesh%xy(:, node) - centre) < norm2(deck%mesh%xy(:, impact%centre_node) - centre)) &
        impact%centre_node = node
    end do
    allocate(impact%pressure(deck%mesh%nnode))
    impact%pressure = 0.0_dp
    impact%ever_active = spread(.false., 1, deck%mesh%nnode)
    impact%pressure_at_force_max = impact%pressure
    impact%pressure_at_alpha_max = impact%pressure
    impact%reaction_at_force_max = impact%pressure
    impact%reaction_at_alpha_max = impact%pressure
    impact%r_at_force_max = deck%mesh%xy(1, :)
    impact%r_at_alpha_max = deck%mesh%xy(1, :)
    impact%stop_reason = 'end of time'
    impact%pad = deck%pad%line > 0
    impact%second = deck%body%line > 0
    if (impact%second .and. present(mass2) .and. present(v)) then
      impact%mass2 = mass2
      impact%body2_mass = sum(mass2(2::2))
      impact%pole2 = deck%pad%surface(1)
      impact%v2 = dot_product(mass2(2::2), v(2::2))/impact%body2_mass
      impact%v2_previous = impact%v2
    end if
    impact%accel_centre = a(node_dof(deck%mesh, impact%centre_node, 2))
    associate (nodal_mass => nodal_field(deck%mesh, mass))               ! (2, nnode), node order
    impact%mass_z = nodal_mass(2, :)
    end associate
    allocate(impact%sensor(size(deck%probes)), impact%t_sensor_max(size(deck%probes)))
    impact%sensor = 0.0_dp
    impact%t_sensor_max = 0.0_dp
    impact%sensor_max = spread(-huge(1.0_dp), 1, size(deck%probes))
    call measure_sensors(impact, deck, a)
  end subroutine impact_start

  !> The rigid-body acceleration (a_r, a_z) of a sensor's region: the
  !> mass-weighted mean sum m_i a_i / sum m_i over its nodes, m the lumped
  !> masses (per radian in axisymmetry, as the region's rings), a in band
  !> order. It is what an accelerometer of that size reads: the rate of
  !> change of the region's momentum over its mass. A rigid translation
  !> gives its acceleration exactly; the mesh-scale ringing of single nodes
  !> averages out over a region many elements wide.
  pure function sensor_acceleration(deck, probe, mass_z, a) result(mean)
    type(deck_t), intent(in) :: deck
    type(probe_t), intent(in) :: probe
    real(dp), intent(in) :: mass_z(:), a(:)
    real(dp) :: mean(2)
    real(dp) :: weight
    integer :: i, node
    mean = 0.0_dp
    weight = 0.0_dp
    do i = 1, size(probe%region)
      node = probe%region(i)
      mean = mean + mass_z(node)*[a(node_dof(deck%mesh, node, 1)), a(node_dof(deck%mesh, node, 2))]
      weight = weight + mass_z(node)
    end do
    if (weight > 0.0_dp) mean = mean/weight
  end function sensor_acceleration

  !> a_z of every sensor now (0 for a probe without RADIUS=).
  pure subroutine measure_sensors(impact, deck, a)
    type(impact_t), intent(inout) :: impact
    type(deck_t), intent(in) :: deck
    real(dp), intent(in) :: a(:)
    real(dp) :: mean(2)
    integer :: k
    do k = 1, size(deck%probes)
      if (deck%probes(k)%radius <= 0.0_dp) cycle
      mean = sensor_acceleration(deck, deck%probes(k), impact%mass_z, a)
      impact%sensor(k) = mean(2)
    end do
  end subroutine measure_sensors

  !> After the step from t - dt to t: first contact (interpolated within the
  !> step at `touch_fraction`, linear in time), force and pressure from the
  !> plate reactions, radius, alpha, the maxima (`new_alpha_max`,
  !> `new_q_max` tell the caller to keep the fields) and the stop criteria.
  !> cm = (u, v, a) of the centre of mass at t, cm_start = (u, v) at t - dt.
  subroutine impact_measure(impact, deck, contact, t, dt, touch_fraction, cm, cm_start, reaction, u, v, a, stress, &
                            new_alpha_max, new_q_max)
    type(impact_t), intent(inout) :: impact
    type(deck_t), intent(in) :: deck
    type(contact_t), intent(in) :: contact
    real(dp), intent(in) :: t, dt, touch_fraction, cm(3), cm_start(2)
    real(dp), intent(in) :: reaction(:), u(:), v(:), a(:), stress(:, :, :)
    logical, intent(out) :: new_alpha_max, new_q_max
    real(dp) :: s(4), since
    integer :: nearest, k
    logical :: first
    new_alpha_max = .false.
    new_q_max = .false.
    associate (m => impact)
    m%contact_nodes = contact_count(contact)
    first = .false.
    if (m%t_contact < 0.0_dp .and. m%contact_nodes > 0) then
      first = .true.
      m%t_contact = t - dt + touch_fraction*dt
      m%u_cm_contact = cm_start(1) + touch_fraction*(cm(1) - cm_start(1))
      m%v_cm_contact = cm_start(2) + touch_fraction*(cm(2) - cm_start(2))
    end if
    if (m%second) then                             ! the second body's centre of mass
      m%u2_previous = m%u2
      m%v2_previous = m%v2
      m%u2 = dot_product(m%mass2(2::2), u(2::2))/m%body2_mass
      m%v2 = dot_product(m%mass2(2::2), v(2::2))/m%body2_mass
      if (first) then
        m%u2_contact = m%u2_previous + touch_fraction*(m%u2 - m%u2_previous)
        m%v2_contact = m%v2_previous + touch_fraction*(m%v2 - m%v2_previous)
      end if
    end if
    m%force = contact_force(deck, contact, reaction)
    call contact_pressure(deck, contact, reaction, m%pressure, m%q)
    m%q_surface = 0.0_dp
    if (contact%active(contact%pole)) then
      if (m%have_surface_tau) then
        m%q_surface = m%q_surface_tau
      else
        if (.not. allocated(m%pole_corners)) m%pole_corners = node_corners(deck%mesh, contact%pole)
        s = corner_stress(stress, m%pole_corners)
        m%q_surface = -s(2)
      end if
    end if
    m%have_surface_tau = .false.
    m%radius = contact_radius(deck, contact)
    m%accel_centre = a(node_dof(deck%mesh, m%centre_node, 2))
    call measure_sensors(m, deck, a)
    if (m%t_contact < 0.0_dp) return
    since = t - m%t_contact
    m%contact_nodes_max = max(m%contact_nodes_max, m%contact_nodes)
    if (m%second) then                                            ! two bodies: the approach of their centres
      m%alpha = m%u_cm_contact - cm(1) + (m%u2 - m%u2_contact)
      m%deformation1 = u(node_dof(deck%mesh, contact%pole, 2)) - cm(1)
      m%deformation2 = m%u2 - u(node_dof(deck%mesh, m%pole2, 2))
      m%deformation1_max = max(m%deformation1_max, m%deformation1)
      m%deformation2_max = max(m%deformation2_max, m%deformation2)
    else
      m%pad_compression = pad_compression(deck, contact, u)
      m%alpha = m%u_cm_contact - cm(1) - m%pad_compression        ! on a pad: the body's own deformation
    end if
    if (m%alpha > m%alpha_max) then
      m%have_before = m%t_alpha_max > 0.0_dp .or. m%alpha_max > 0.0_dp   ! a sample before this one since contact
      m%alpha_before = m%alpha_previous
      m%t_before = m%t_previous
      m%have_after = .false.
      m%alpha_max = m%alpha
      m%t_alpha_max = since
      new_alpha_max = .true.
    else if (m%alpha_max > 0.0_dp) then
      m%alpha_passed = .true.
      if (.not. m%have_after) then
        m%have_after = .true.
        m%alpha_after = m%alpha
        m%t_after = since
      end if
    end if
    m%alpha_previous = m%alpha
    m%t_previous = since
    m%ever_active = m%ever_active .or. contact%active
    if (new_alpha_max) call keep_profile(m%pressure_at_alpha_max, m%r_at_alpha_max, m%reaction_at_alpha_max)
    if (m%force > m%force_max) call keep_profile(m%pressure_at_force_max, m%r_at_force_max, m%reaction_at_force_max)
    if (m%q > m%q_max) then
      m%q_max = m%q
      m%t_q_max = since
      new_q_max = .true.
    end if
    call keep_max(m%q_surface, m%q_surface_max, m%t_q_surface_max)
    call keep_max(m%force, m%force_max, m%t_force_max)
    call keep_max(m%pad_compression, m%pad_compression_max, m%t_pad_compression_max)
    if (m%pad) then
      m%pad_stress = -minval(stress(2, :, deck%pad%first_element:))
      call keep_max(m%pad_stress, m%pad_stress_max, m%t_pad_stress_max)
    end if
    call keep_max(m%accel_centre, m%accel_max, m%t_accel_max)
    do k = 1, size(m%sensor)
      if (deck%probes(k)%radius > 0.0_dp) call keep_max(m%sensor(k), m%sensor_max(k), m%t_sensor_max(k))
    end do
    m%radius_max = max(m%radius_max, m%radius)
    m%accel_cm_max = max(m%accel_cm_max, cm(3))
    ! The paper's criterion: the free node nearest the plate moves up.
    nearest = 0
    if (.not. m%second) nearest = nearest_free_node(deck, contact, u)   ! the plate's criterion only
    if (.not. m%paper_fired .and. nearest > 0) then
      if (v(node_dof(deck%mesh, nearest, 2)) > 0.0_dp) then
        m%paper_fired = .true.
        m%t_paper = since
      end if
    end if
    select case (deck%stop_at)
    case (stop_at_max_deformation)            ! and alpha past its maximum: a wave cannot cut the loading short
      if (m%paper_fired .and. m%alpha_passed) then
        m%stopped = .true.
        m%stop_reason = 'maximum deformation'
      end if
    case (stop_at_separation)
      if (m%second) then                    ! two bodies: no contact and moving apart
        if (m%contact_nodes == 0 .and. cm(2) - m%v2 > 0.0_dp) then
          m%stopped = .true.
          m%stop_reason = 'separation'
          m%t_separation = since
          m%v_separation = cm(2)
          m%v2_separation = m%v2
        end if
      else if (m%contact_nodes == 0 .and. cm(2) > 0.0_dp) then
        m%stopped = .true.
        m%stop_reason = 'separation'
        m%t_separation = since
        m%v_separation = cm(2)
      end if
    end select
    end associate

  contains

    !> The contact pressure now, the deformed r of every node and the plate
    !> reaction in z of each contact node (as contact_force sums it).
    subroutine keep_profile(pressure, r, nodal_reaction)
      real(dp), intent(inout) :: pressure(:), r(:), nodal_reaction(:)
      real(dp), allocatable :: displacement(:, :)
      integer :: node
      displacement = nodal_field(deck%mesh, u)
      pressure = impact%pressure
      r = deck%mesh%xy(1, :) + displacement(1, :)
      nodal_reaction = 0.0_dp
      do node = 1, deck%mesh%nnode
        if (contact%active(node)) nodal_reaction(node) = reaction(node_dof(deck%mesh, node, 2))
      end do
      if (deck%settings%geometry == geometry_axisymmetric) nodal_reaction = 2.0_dp*pi*nodal_reaction
    end subroutine keep_profile

    pure subroutine keep_max(value, maximum, at)
      real(dp), intent(in) :: value
      real(dp), intent(inout) :: maximum, at
      if (value <= maximum) return
      maximum = value
      at = since
    end subroutine keep_max
  end subroutine impact_measure

  !> q_surface, the surface stress -sigma_z at the pole, at t + tau (tau =
  !> theta dt), where Wilson-theta holds equilibrium, as the plate reactions
  !> are taken: sigma_t plus the increment over tau of the elements at the
  !> pole, from dU_tau with the moduli over tau (eqs. [13], [14]) and, with
  !> memory, the history stress over tau (eq. [23]); extrapolated to the
  !> pole and averaged as node_stress. Called in the step, before the
  !> stresses move on to t + dt; impact_measure reports it. At t + dt the
  !> stress carries the stiff dilatational modes that a node touching the
  !> plate excites, which Wilson-theta overshoots and then damps only by its
  !> limit spectral radius (-0.78 per step at theta = 1.4): with nu = 0.4999
  !> (B-bar, level 3, dt = 1e-5 s) -sigma_z at t + dt was 90.7 MPa at the
  !> first step against q = 2.5 MPa, then +-26, +-18, ... MPa; at t + tau it
  !> is 0.33 MPa there and 2.43 MPa at the peak. With another integrator
  !> (INTEGRATOR card) "t + tau" is its solve point: the end of the (sub-)step,
  !> where it holds equilibrium (theta = 1).
  subroutine impact_surface_stress(impact, deck, contact, stress, delta_tau, over_tau, memory, state)
    type(impact_t), intent(inout) :: impact
    type(deck_t), intent(in) :: deck
    type(contact_t), intent(in) :: contact
    real(dp), intent(in) :: stress(:, :, :)          !< at t, (4, 4, nelem)
    real(dp), intent(in) :: delta_tau(:)             !< dU_tau, band order
    type(step_coefficients_t), intent(in) :: over_tau(:)   !< per material, for the step tau
    logical, intent(in) :: memory                    !< the state has histories
    type(viscoelastic_state_t), intent(in) :: state
    real(dp), allocatable :: local(:, :, :)
    integer, allocatable :: corners(:, :)
    real(dp) :: increment(4, gauss_count), s(4)
    integer :: k, e, g, nterm, slot
    impact%have_surface_tau = .false.
    if (.not. contact%active(contact%pole)) return
    if (.not. allocated(impact%pole_corners)) impact%pole_corners = node_corners(deck%mesh, contact%pole)
    associate (mesh => deck%mesh, pole => impact%pole_corners)
    allocate(local(4, gauss_count, size(pole, 2)))
    corners = pole
    do k = 1, size(pole, 2)
      e = pole(2, k)
      corners(2, k) = k
      associate (c => over_tau(mesh%element_material(e)), material => deck%materials(mesh%element_material(e)))
      increment = element_strains(deck%settings%geometry, mesh%xy(:, mesh%connectivity(:, e)), &
                                  gather(mesh, e, delta_tau), deck%settings%formulation)
      nterm = 0
      if (memory) nterm = element_terms(state, e)
      do g = 1, gauss_count
        local(:, g, k) = stress(:, g, e) + stress_from_strain(c%shear, c%bulk, increment(:, g))
        if (nterm == 0) cycle
        slot = state%first(e) + (g - 1)*nterm
        local(:, g, k) = local(:, g, k) + history_stress(material, c, state%history(:, slot:slot + nterm - 1))
      end do
      end associate
    end do
    end associate
    s = corner_stress(local, corners)
    impact%q_surface_tau = -s(2)
    impact%have_surface_tau = .true.
  end subroutine impact_surface_stress

  !> The contact pressure over radius, p(r), at the largest plate force
  !> (t_force_max_ms) and at the largest sampled approach (t_alpha_max_step_ms):
  !> one row per surface node that was on the plate at some step, in order of
  !> its undeformed r; its deck number, undeformed r, and deformed r and
  !> pressure (the recovered nodal pressure, contact_pressure) at each instant,
  !> and its plate reaction in z at each instant, N (reaction_z_*_ring_N: whole
  !> ring, 2 pi times the per-radian nodal reaction, in axisymmetry; per metre
  !> in plane strain): each column sums to the plate force force_N then.
  subroutine pressure_table(impact, deck, record)
    type(impact_t), intent(in) :: impact
    type(deck_t), intent(in) :: deck
    type(record_t), intent(inout) :: record
    integer, allocatable :: nodes(:)
    integer :: i, node
    nodes = pack([(i, i = 1, deck%mesh%nnode)], impact%ever_active)
    nodes = nodes(sorted_order(deck%mesh%xy(1, nodes)))   ! by undeformed r
    record%pressure%columns = [character(len=27) :: 'node', 'r_mm', 'r_force_max_mm', 'p_force_max_MPa', &
                               'r_alpha_max_mm', 'p_alpha_max_MPa', 'reaction_z_force_max_ring_N', &
                               'reaction_z_alpha_max_ring_N']
    allocate(record%pressure%values(size(record%pressure%columns), size(nodes)))
    do i = 1, size(nodes)
      node = nodes(i)
      record%pressure%values(:, i) = [real(deck%mesh%node_id(node), dp), 1.0e3_dp*deck%mesh%xy(1, node), &
        1.0e3_dp*impact%r_at_force_max(node), 1.0e-6_dp*impact%pressure_at_force_max(node), &
        1.0e3_dp*impact%r_at_alpha_max(node), 1.0e-6_dp*impact%pressure_at_alpha_max(node), &
        impact%reaction_at_force_max(node), impact%reaction_at_alpha_max(node)]
    end do
  end subroutine pressure_table

  !> History columns of an impact (t_ms and alpha_mm are filled by impact_summary).
  !> With a pad, also its compression at the axis.
  !> With a second BODY, its centre of mass (displacement, velocity).
  pure function impact_columns(pad, second) result(columns)
    logical, intent(in) :: pad, second
    character(len=18), allocatable :: columns(:)
    columns = [character(len=18) :: 't_ms', 'alpha_mm', 'force_N', 'q_MPa', 'q_surface_MPa', 'contact_radius_mm', &
               'accel_center_g', 'n_contact']
    if (pad) columns = [character(len=18) :: columns, 'pad_compression_mm']
    if (second) columns = [character(len=18) :: columns, 'body2_uz_cm_m', 'body2_vz_cm_m_s']
  end function impact_columns

  !> The values of impact_columns now.
  pure function impact_row(impact) result(row)
    type(impact_t), intent(in) :: impact
    real(dp), allocatable :: row(:)
    row = [0.0_dp, 0.0_dp, impact%force, 1.0e-6_dp*impact%q, 1.0e-6_dp*impact%q_surface, 1.0e3_dp*impact%radius, &
           impact%accel_centre/g_unit, real(impact%contact_nodes, dp)]
    if (impact%pad) row = [row, 1.0e3_dp*impact%pad_compression]
    if (impact%second) row = [row, impact%u2, impact%v2]
  end function impact_row

  !> The impact keys of the summary (doc/outputs.md), the Hertz reference for
  !> `mass` (kg, whole body), the warnings, and the history columns t_ms and
  !> alpha_mm from t_s and uz_cm_m now that first contact is known.
  subroutine impact_summary(impact, deck, contact, record, mass, t_end)
    type(impact_t), intent(in) :: impact
    type(deck_t), intent(in) :: deck
    type(contact_t), intent(in) :: contact
    type(record_t), intent(inout) :: record
    real(dp), intent(in) :: mass, t_end
    integer :: row, t_column, uz_column, t_ms_column, alpha_column, k
    real(dp) :: alpha_peak, t_peak
    associate (m => impact)
    if (m%second) then
      call record_put(record, 'contact_pair', 'BODY '//trim(merge('STICK', 'SLIP ', deck%body%stick))// &
                      trim(merge(' RELEASE=YES', ' RELEASE=NO ', deck%body%release)))
      call record_put_real(record, 'body2_mass_kg', mass_factor(deck)*m%body2_mass)
      call record_put_real(record, 'body2_uz_cm_m', m%u2)
      call record_put_real(record, 'body2_vz_cm_m_s', m%v2)
    else
      call record_put_real(record, 'plate_z_m', deck%plate%z)
      call record_put(record, 'plate', trim(merge('STICK', 'SLIP ', deck%plate%stick))// &
                      trim(merge(' RELEASE=YES', ' RELEASE=NO ', deck%plate%release)))
    end if
    call record_put(record, 'stop_at', stop_name(deck%stop_at))
    call record_put(record, 'stop_reason', m%stop_reason)
    call record_put_integer(record, 'contact_iterations', contact%iterations)
    call record_put_integer(record, 'contact_nodes_max', m%contact_nodes_max)
    if (m%t_contact < 0.0_dp .and. m%second) then
      call record_warn(record, 'the bodies never touched (BODY GAP = '//short_real(deck%body%gap)// &
        ' m): no contact results', file=deck%cards%file, line=deck%body%line, card='BODY')
      call record_put(record, 'contact', 'none')
    else if (m%t_contact < 0.0_dp) then
      call record_warn(record, 'the body never touched the plate (PLATE Z = '//short_real(deck%plate%z)// &
        ' m): no contact results', file=deck%cards%file, line=deck%plate%line, card='PLATE')
      call record_put(record, 'contact', 'none')
    else
      call record_put_real(record, 'time_first_contact_s', m%t_contact)
      call record_put_real(record, 'impact_velocity_m_s', -m%v_cm_contact)
      call record_put_real(record, 't_stop_ms', 1.0e3_dp*(t_end - m%t_contact))
      if (m%paper_fired) call record_put_real(record, 't_paper_criterion_ms', 1.0e3_dp*m%t_paper)
      if (m%stop_reason == 'end of time' .and. deck%stop_at /= stop_at_tend) then
        ! The criterion was not reached: the largest approach so far is not the
        ! impact's maximum, and is not named as one.
        call record_put_real(record, 'alpha_largest_mm', 1.0e3_dp*m%alpha_max)
        call record_put_real(record, 't_alpha_largest_ms', 1.0e3_dp*m%t_alpha_max)
      else
        call peak_of_parabola(m, alpha_peak, t_peak)
        call record_put_real(record, 'alpha_max_mm', 1.0e3_dp*alpha_peak)
        call record_put_real(record, 't_alpha_max_ms', 1.0e3_dp*t_peak)
        call record_put_real(record, 'alpha_max_step_mm', 1.0e3_dp*m%alpha_max)
        call record_put_real(record, 't_alpha_max_step_ms', 1.0e3_dp*m%t_alpha_max)
      end if
      call record_put_real(record, 'q_max_MPa', 1.0e-6_dp*m%q_max)
      call record_put_real(record, 't_q_max_ms', 1.0e3_dp*m%t_q_max)
      call record_put_real(record, 'q_surface_max_MPa', 1.0e-6_dp*m%q_surface_max)
      call record_put_real(record, 't_q_surface_max_ms', 1.0e3_dp*m%t_q_surface_max)
      call record_put_real(record, 'force_max_N', m%force_max)
      call record_put_real(record, 't_force_max_ms', 1.0e3_dp*m%t_force_max)
      call record_put_real(record, 'contact_radius_max_mm', 1.0e3_dp*m%radius_max)
      if (m%pad) then
        call record_put_real(record, 'pad_compression_max_mm', 1.0e3_dp*m%pad_compression_max)
        call record_put_real(record, 't_pad_compression_max_ms', 1.0e3_dp*m%t_pad_compression_max)
        call record_put_real(record, 'pad_stress_z_max_MPa', 1.0e-6_dp*m%pad_stress_max)
        call record_put_real(record, 't_pad_stress_z_max_ms', 1.0e3_dp*m%t_pad_stress_max)
      end if
      call record_put_real(record, 'accel_center_max_g', m%accel_max/g_unit)
      call record_put_real(record, 't_accel_center_max_ms', 1.0e3_dp*m%t_accel_max)
      call record_put_real(record, 'accel_cm_max_g', m%accel_cm_max/g_unit)
      do k = 1, size(deck%probes)
        if (deck%probes(k)%radius <= 0.0_dp) cycle
        call record_put_real(record, 'probe_'//deck%probes(k)%name//'_sensor_accel_max_g', m%sensor_max(k)/g_unit)
        call record_put_real(record, 't_probe_'//deck%probes(k)%name//'_sensor_accel_max_ms', &
                             1.0e3_dp*m%t_sensor_max(k))
      end do
      if (m%second) then
        call record_put_real(record, 'body2_impact_velocity_m_s', m%v2_contact)
        call record_put_real(record, 'approach_speed_m_s', m%v2_contact - m%v_cm_contact)
        call record_put_real(record, 'deformation1_max_mm', 1.0e3_dp*m%deformation1_max)
        call record_put_real(record, 'deformation2_max_mm', 1.0e3_dp*m%deformation2_max)
      end if
      if (m%t_separation >= 0.0_dp .and. m%second) then
        call record_put_real(record, 'contact_duration_ms', 1.0e3_dp*m%t_separation)
        call record_put_real(record, 'rebound_velocity_m_s', m%v_separation)
        call record_put_real(record, 'body2_rebound_velocity_m_s', m%v2_separation)
        call record_put_real(record, 'separation_speed_m_s', m%v_separation - m%v2_separation)
        call record_put_real(record, 'coefficient_of_restitution', (m%v_separation - m%v2_separation)/ &
                             max(m%v2_contact - m%v_cm_contact, tiny(1.0_dp)))
        call record_put_real(record, 'energy_absorbed_J', 0.5_dp*mass*(m%v_cm_contact**2 - m%v_separation**2) + &
          0.5_dp*mass_factor(deck)*m%body2_mass*(m%v2_contact**2 - m%v2_separation**2))
      else if (m%t_separation >= 0.0_dp) then
        call record_put_real(record, 'contact_duration_ms', 1.0e3_dp*m%t_separation)
        call record_put_real(record, 'rebound_velocity_m_s', m%v_separation)
        call record_put_real(record, 'coefficient_of_restitution', m%v_separation/max(-m%v_cm_contact, tiny(1.0_dp)))
        call record_put_real(record, 'energy_absorbed_J', 0.5_dp*mass*(m%v_cm_contact**2 - m%v_separation**2))
      end if
      if (m%second) then
        call put_two_body_hertz(deck, record, mass, mass_factor(deck)*m%body2_mass, m%v2_contact - m%v_cm_contact)
      else
        call put_hertz_summary(deck, record, mass, m%v_cm_contact)
      end if
      call pressure_table(m, deck, record)
    end if
    if (m%stop_reason == 'end of time' .and. deck%stop_at /= stop_at_tend) call record_warn(record, &
      'the run reached the end of its TIME cards before STOP AT='//stop_name(deck%stop_at)//': the approach is '// &
      'reported as alpha_largest_mm, not as a maximum, and the other maxima are those of the time simulated, '// &
      'not of the whole impact; a later TEND reaches them', &
      file=deck%cards%file, line=stop_line(deck), card='STOP')
    t_column = record_column(record, 't_s')
    uz_column = record_column(record, 'uz_cm_m')
    t_ms_column = record_column(record, 't_ms')
    alpha_column = record_column(record, 'alpha_mm')
    do row = 1, record%nrow
      record%history(t_ms_column, row) = 1.0e3_dp*(record%history(t_column, row) - max(m%t_contact, 0.0_dp))
      record%history(alpha_column, row) = 0.0_dp
      if (m%t_contact >= 0.0_dp) record%history(alpha_column, row) = &
        1.0e3_dp*(m%u_cm_contact - record%history(uz_column, row))
      if (m%pad) record%history(alpha_column, row) = record%history(alpha_column, row) - &
        record%history(record_column(record, 'pad_compression_mm'), row)
      if (m%second .and. m%t_contact >= 0.0_dp) record%history(alpha_column, row) = &
        record%history(alpha_column, row) + 1.0e3_dp*(record%history(record_column(record, 'body2_uz_cm_m'), row) - &
                                                      m%u2_contact)
    end do
    end associate
  end subroutine impact_summary

  !> The maximum of alpha(t) between steps: the vertex of the parabola
  !> through the largest sample and its two neighbours (alpha is smooth
  !> there: the centre of mass decelerates). The sampled maximum is off by up
  !> to dt/2 in time; the vertex by O(dt^2). Falls back to the sample when a
  !> neighbour is missing or the three points are not concave.
  pure subroutine peak_of_parabola(m, alpha_peak, t_peak)
    type(impact_t), intent(in) :: m
    real(dp), intent(out) :: alpha_peak, t_peak
    real(dp) :: h1, h2, d1, d2, denominator, slope, curvature
    alpha_peak = m%alpha_max
    t_peak = m%t_alpha_max
    if (.not. (m%have_before .and. m%have_after)) return
    h1 = m%t_before - m%t_alpha_max                   ! < 0
    h2 = m%t_after - m%t_alpha_max                    ! > 0
    d1 = m%alpha_before - m%alpha_max                 ! <= 0
    d2 = m%alpha_after - m%alpha_max                  ! < 0
    denominator = h1*h2*(h2 - h1)
    if (h1 >= 0.0_dp .or. h2 <= 0.0_dp .or. denominator == 0.0_dp) return
    ! alpha = alpha_max + slope s + curvature s^2, s = t - t_alpha_max, through (h1, d1) and (h2, d2)
    curvature = (d2*h1 - d1*h2)/denominator
    slope = (d1*h2**2 - d2*h1**2)/denominator
    if (curvature >= 0.0_dp) return
    t_peak = m%t_alpha_max - slope/(2.0_dp*curvature)
    if (t_peak < m%t_before .or. t_peak > m%t_after) then
      t_peak = m%t_alpha_max
      return
    end if
    alpha_peak = m%alpha_max - slope**2/(4.0_dp*curvature)
  end subroutine peak_of_parabola
  !> The line of the STOP card, or of the PLATE card when STOP is not given
  !> (the default criterion comes with the plate).
  pure integer function stop_line(deck)
    type(deck_t), intent(in) :: deck
    stop_line = deck%stop_line
    if (stop_line == 0) stop_line = max(deck%plate%line, deck%body%line)
  end function stop_line

  !> Whole-body masses from per-radian ones: 2 pi in axisymmetry (a BODY's geometry).
  pure real(dp) function mass_factor(deck) result(factor)
    type(deck_t), intent(in) :: deck
    factor = 1.0_dp
    if (deck%settings%geometry == geometry_axisymmetric) factor = 2.0_dp*pi
  end function mass_factor
end module visco2d_impact
