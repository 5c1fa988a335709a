!> The contact extension: a rigid flat plate z = Z that the body may touch
!> (the paper's "Numerical Procedure"). The plate is fixed. A boundary node
!> that reaches it gets an adjusted-displacement condition (it is put on the
!> plate) and the same increment is repeated; from then on it is held:
!> STICK holds u_r and u_z, SLIP (frictionless) u_z only. With RELEASE=YES a
!> contact node whose reaction turns tensile is freed again.
!>
!> Also here: the contact pressure recovered from the nodal reactions (a
!> consistent boundary-mass projection), the contact radius and force, the
!> static indentation solver (STATIC with a PLATE) and the Hertz /
!> Timoshenko-Goodier impact of a sphere on a rigid plate, eqs. [43]-[45],
!> built in as the analytic reference.
module visco2d_contact
  use, intrinsic :: iso_fortran_env, only: int64
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use visco2d_kinds, only: dp, pi, geometry_axisymmetric, geometry_tolerance
  use visco2d_error, only: error_t, set_error
  use visco2d_strings, only: itoa, gtoa
  use visco2d_deck, only: deck_t
  use visco2d_mesh, only: side_nodes
  use visco2d_renumber, only: sort_integers
  use visco2d_element, only: element_lumped_mass
  use visco2d_assembly, only: node_dof, scatter_add, band_vector, assemble_stiffness, external_load, gravity_load, &
                              support_mask, prescribed_displacement
  use visco2d_banded, only: band_matrix_t, band_constrain_matrix, band_constrain_rhs, band_factor, band_solve_many, &
                            band_multiply
  use visco2d_static, only: static_solution_t, solve_static, static_record, node_stress, singular_message
  use visco2d_record, only: record_t, record_put, record_put_real, record_put_integer
  use visco2d_bruise, only: bruise_static
  implicit none
  private

  public :: contact_t, hertz_t
  public :: contact_create, contact_held_dofs, contact_begin_increment, contact_search, contact_count
  public :: contact_pressure, contact_force, contact_radius, contact_gap, nearest_free_node
  public :: volume_weights, hertz_impact, solve_static_contact, put_hertz_summary
  public :: hertz_time_constant, hertz_duration_constant

  !> t_m = 1.4716 alpha_m / V: the exact constant of Hertz impact (the paper prints 1.47).
  real(dp), parameter :: hertz_time_constant = 1.4716_dp
  !> Contact duration 2 t_m = 2.9432 alpha_m / V.
  real(dp), parameter :: hertz_duration_constant = 2.0_dp*hertz_time_constant

  !> The state of contact with the plate.
  type :: contact_t
    real(dp) :: z_plate = 0.0_dp
    logical :: stick = .true.
    logical :: release = .false.
    real(dp) :: tolerance = 0.0_dp              !< m: a node closer than this is on the plate
    integer, allocatable :: candidates(:)       !< boundary nodes (not the axis) that may touch
    integer, allocatable :: edges(:, :)         !< (2, nedge) boundary edges off the axis
    logical, allocatable :: active(:)           !< (nnode) held on the plate
    logical, allocatable :: touched(:)          !< (nnode) put on the plate in this increment
    logical, allocatable :: let_go(:)           !< (nnode) freed in this increment
    integer :: pole = 0                         !< lowest boundary node (nearest the axis): q is reported here
    integer :: iterations = 0                   !< increments repeated because the contact set changed
  end type contact_t

  !> States of a node on the static contact path.
  integer, parameter :: node_free = 0      !< off the plate
  integer, parameter :: node_stuck = 1     !< on the plate, u_r and u_z held (STICK)
  integer, parameter :: node_sliding = 2   !< on the plate, u_z held (SLIP; a STICK node freed at zero force)
  !> Block changes at one load factor that may fail to lower the count of
  !> violating nodes before they change one at a time (Judice and Pires).
  integer, parameter :: strikes_allowed = 10
  !> The error of a static contact solution that overflowed.
  character(*), parameter :: not_finite_message = 'the static contact solution is not a finite number (it '// &
    'overflowed): the moduli, loads or sizes of the deck are out of any physical range; no results were written'
  !> Two load factors closer than this are the same point of the static path.
  real(dp), parameter :: same_factor = 1.0e-12_dp

  !> The static contact path: its state at load factor lambda and the
  !> response u = base + lambda rate of the current contact set.
  type :: static_path_t
    real(dp) :: load_factor = 0.0_dp             !< lambda, 0 .. 1
    integer, allocatable :: state(:)             !< (nnode) node_free, node_stuck, node_sliding
    integer, allocatable :: changes(:)           !< (nnode) changes of state at this load factor
    logical, allocatable :: freed_here(:)        !< (nnode) freed from sticking at this load factor
    real(dp), allocatable :: values(:)           !< (2 nnode) held displacements (band order)
    real(dp), allocatable :: base(:), rate(:)    !< u_0 and u_1 of the current set
    real(dp), allocatable :: reaction_base(:), reaction_rate(:)
    integer :: solves = 0                        !< factorizations along the path
    integer :: best_violations = huge(1)         !< fewest nodes past their limit at this load factor
    integer :: strikes = 0                       !< block changes since that count last fell
  end type static_path_t

  !> The stiffness and the full load of a static contact problem.
  type :: held_system_t
    type(band_matrix_t) :: stiffness             !< S, unconstrained
    real(dp), allocatable :: load(:)             !< loads and gravity
    real(dp), allocatable :: prescribed(:)       !< prescribed support displacements
    logical, allocatable :: supports(:)          !< supported equations
  end type held_system_t

  !> Hertz impact of an elastic sphere on a rigid plate (Timoshenko and
  !> Goodier), SI units.
  type :: hertz_t
    real(dp) :: alpha_max = 0.0_dp       !< m, eq. [43]
    real(dp) :: t_alpha_max = 0.0_dp     !< s, eq. [44] with 1.4716
    real(dp) :: q_max = 0.0_dp           !< Pa, eq. [45]
    real(dp) :: force_max = 0.0_dp       !< N, (4/3) E/(1 - nu^2) sqrt(R) alpha_m^(3/2)
    real(dp) :: contact_radius = 0.0_dp  !< m, sqrt(R alpha_m)
    real(dp) :: duration = 0.0_dp        !< s, 2.9432 alpha_m / V
  end type hertz_t

contains

  !> Eqs. [43]-[45]: the maxima of a Hertz impact at speed V of a sphere of
  !> mass M and radius R (E, nu) on a rigid plate.
  pure function hertz_impact(young, poisson, radius, mass, speed) result(hertz)
    real(dp), intent(in) :: young, poisson, radius, mass, speed
    type(hertz_t) :: hertz
    real(dp) :: modulus
    modulus = young/(1.0_dp - poisson**2)
    hertz%alpha_max = (15.0_dp*mass*speed**2/(16.0_dp*modulus*sqrt(radius)))**0.4_dp      ! eq. [43]
    hertz%t_alpha_max = hertz_time_constant*hertz%alpha_max/abs(speed)                   ! eq. [44]
    hertz%q_max = 2.0_dp*modulus/pi*sqrt(hertz%alpha_max/radius)                         ! eq. [45]
    hertz%force_max = 4.0_dp/3.0_dp*modulus*sqrt(radius)*hertz%alpha_max**1.5_dp
    hertz%contact_radius = sqrt(radius*hertz%alpha_max)
    hertz%duration = hertz_duration_constant*hertz%alpha_max/abs(speed)
  end function hertz_impact

  !> The Hertz reference of an impact at `speed` of a body of `mass`, in the
  !> summary (hertz_* keys), when the body is a generated sphere (MESH SPHERE)
  !> of one material: E and nu are the material's instantaneous values (its
  !> elastic constants for an elastic material), R = half the pole-to-pole height.
  !> Left out, with the key hertz_reference saying why, when it would mean
  !> nothing: V not small against the bar wave speed sqrt(E/rho) (Hertz's
  !> theory is quasi-static; this also keeps V^2 from overflowing), a value
  !> that is not a finite number, a maximum approach alpha_m below the
  !> round-off of the node positions (geometry_tolerance R; V = 4.9e-324 m/s
  !> gives alpha_m = 0 and t_m = 0/V), or alpha_m not below R (Hertz's
  !> contact radius sqrt(R alpha_m) must be small against R).
  subroutine put_hertz_summary(deck, record, mass, speed)
    type(deck_t), intent(in) :: deck
    type(record_t), intent(inout) :: record
    real(dp), intent(in) :: mass, speed
    type(hertz_t) :: hertz
    real(dp) :: radius, wave_speed
    if (.not. allocated(deck%mesh%source)) return
    if (deck%mesh%source /= 'SPHERE' .or. size(deck%materials) /= 1) return
    if (speed == 0.0_dp) then
      call record_put(record, 'hertz_reference', 'none: the body touched the plate at rest (V = 0)')
      return
    end if
    radius = 0.5_dp*(maxval(deck%mesh%xy(2, :)) - minval(deck%mesh%xy(2, :)))
    associate (material => deck%materials(1))
    wave_speed = sqrt(material%young/max(material%density, tiny(1.0_dp)))
    if (.not. abs(speed) < wave_speed) then
      call record_put(record, 'hertz_reference', 'none: V = '//gtoa(abs(speed))//' m/s is not small against the '// &
                      'wave speed sqrt(E/rho) = '//gtoa(wave_speed)//' m/s (Hertz impact is quasi-static)')
      return
    end if
    hertz = hertz_impact(material%young, material%poisson, radius, mass, speed)
    if (.not. hertz_finite(hertz)) then
      call record_put(record, 'hertz_reference', 'none: not a finite number at V = '//gtoa(abs(speed))//' m/s')
      return
    end if
    if (hertz%alpha_max <= geometry_tolerance*radius) then
      call record_put(record, 'hertz_reference', 'none: V = '//gtoa(abs(speed))//' m/s is too small (alpha_m = '// &
                      gtoa(hertz%alpha_max)//' m, below the round-off of the node positions)')
      return
    end if
    if (hertz%alpha_max >= radius) then
      call record_put(record, 'hertz_reference', 'none: alpha_m = '//gtoa(hertz%alpha_max)//' m is not small '// &
                      'against R = '//gtoa(radius)//' m')
      return
    end if
    call record_put_real(record, 'hertz_young_Pa', material%young)
    call record_put_real(record, 'hertz_poisson', material%poisson)
    end associate
    call record_put_real(record, 'hertz_radius_m', radius)
    call record_put_real(record, 'hertz_mass_kg', mass)
    call record_put_real(record, 'hertz_speed_m_s', abs(speed))
    call record_put_real(record, 'hertz_alpha_max_mm', 1.0e3_dp*hertz%alpha_max)
    call record_put_real(record, 'hertz_t_alpha_max_ms', 1.0e3_dp*hertz%t_alpha_max)
    call record_put_real(record, 'hertz_q_max_MPa', 1.0e-6_dp*hertz%q_max)
    call record_put_real(record, 'hertz_force_max_N', hertz%force_max)
    call record_put_real(record, 'hertz_contact_radius_mm', 1.0e3_dp*hertz%contact_radius)
    call record_put_real(record, 'hertz_contact_duration_ms', 1.0e3_dp*hertz%duration)
  end subroutine put_hertz_summary

  !> Every value of a Hertz reference, and its values in the summary's units, are finite numbers.
  pure logical function hertz_finite(hertz) result(finite)
    type(hertz_t), intent(in) :: hertz
    real(dp) :: values(6)
    values = [hertz%alpha_max, hertz%t_alpha_max, hertz%q_max, hertz%force_max, hertz%contact_radius, hertz%duration]
    finite = all(ieee_is_finite(values)) .and. all(ieee_is_finite(values*1.0e3_dp)) .and. &
             all(ieee_is_finite(values*1.0e-6_dp))
  end function hertz_finite

  !> The candidate nodes and edges (element sides that belong to one element
  !> only, except those on the axis r = 0 of an axisymmetric body), the plate,
  !> and the nodes that start on it.
  subroutine contact_create(deck, contact)
    type(deck_t), intent(in) :: deck
    type(contact_t), intent(out) :: contact
    integer(int64), allocatable :: keys(:)
    integer, allocatable :: order(:), pairs(:, :)
    logical, allocatable :: boundary(:)
    integer :: e, side, a, b, i, count, nedge
    logical :: unique
    associate (mesh => deck%mesh)
    contact%z_plate = deck%plate%z
    contact%stick = deck%plate%stick
    contact%release = deck%plate%release
    contact%tolerance = geometry_tolerance*mesh%size
    allocate(keys(4*mesh%nelem), pairs(2, 4*mesh%nelem))
    count = 0
    do e = 1, mesh%nelem
      do side = 1, 4
        call side_nodes(mesh, e, side, a, b)
        count = count + 1
        pairs(:, count) = [min(a, b), max(a, b)]
        keys(count) = int(pairs(1, count), int64)*int(mesh%nnode + 1, int64) + int(pairs(2, count), int64)
      end do
    end do
    call sort_integers(keys, order)
    allocate(contact%edges(2, count), boundary(mesh%nnode))
    boundary = .false.
    nedge = 0
    do i = 1, count
      unique = .true.
      if (i > 1) unique = keys(order(i)) /= keys(order(i - 1))
      if (i < count) unique = unique .and. keys(order(i)) /= keys(order(i + 1))
      if (.not. unique) cycle
      a = pairs(1, order(i))
      b = pairs(2, order(i))
      if (deck%geometry == geometry_axisymmetric .and. mesh%xy(1, a) == 0.0_dp .and. mesh%xy(1, b) == 0.0_dp) cycle
      nedge = nedge + 1
      contact%edges(:, nedge) = [a, b]
      boundary(a) = .true.
      boundary(b) = .true.
    end do
    contact%edges = contact%edges(:, 1:nedge)
    contact%candidates = pack([(i, i = 1, mesh%nnode)], boundary)
    allocate(contact%active(mesh%nnode), contact%touched(mesh%nnode), contact%let_go(mesh%nnode))
    contact%active = .false.
    contact%touched = .false.
    contact%let_go = .false.
    ! The pole: the lowest candidate, the one nearest the axis among equals.
    contact%pole = contact%candidates(1)
    do i = 2, size(contact%candidates)
      a = contact%candidates(i)
      if (mesh%xy(2, a) < mesh%xy(2, contact%pole) - contact%tolerance .or. &
          (abs(mesh%xy(2, a) - mesh%xy(2, contact%pole)) <= contact%tolerance .and. &
           abs(mesh%xy(1, a)) < abs(mesh%xy(1, contact%pole)))) contact%pole = a
    end do
    end associate
  end subroutine contact_create

  !> Gap z + u_z - Z of a node (m), u the displacement vector in band order.
  pure real(dp) function contact_gap(deck, contact, u, node) result(gap)
    type(deck_t), intent(in) :: deck
    type(contact_t), intent(in) :: contact
    real(dp), intent(in) :: u(:)
    integer, intent(in) :: node
    gap = deck%mesh%xy(2, node) + u(node_dof(deck%mesh, node, 2)) - contact%z_plate
  end function contact_gap

  !> The equations held by contact: u_z of every contact node, and u_r too with STICK.
  function contact_held_dofs(deck, contact) result(held)
    type(deck_t), intent(in) :: deck
    type(contact_t), intent(in) :: contact
    logical :: held(2*deck%mesh%nnode)
    integer :: i, node
    held = .false.
    do i = 1, size(contact%candidates)
      node = contact%candidates(i)
      if (.not. contact%active(node)) cycle
      held(node_dof(deck%mesh, node, 2)) = .true.
      if (contact%stick) held(node_dof(deck%mesh, node, 1)) = .true.
    end do
  end function contact_held_dofs

  !> Start a new increment: nothing touched or freed in it yet.
  pure subroutine contact_begin_increment(contact)
    type(contact_t), intent(inout) :: contact
    contact%touched = .false.
    contact%let_go = .false.
  end subroutine contact_begin_increment

  !> After a trial increment du from u: put on the plate every free candidate
  !> that went through it, and (RELEASE=YES) free every contact node whose
  !> plate reaction (z, per radian) is tensile. A node
  !> changes state at most once per increment, so the repetition ends.
  !> `fraction` is the earliest crossing of the plate within the increment
  !> (0..1, linear in time), 1 if nothing touched.
  subroutine contact_search(deck, contact, u, du, reaction, changed, fraction)
    type(deck_t), intent(in) :: deck
    type(contact_t), intent(inout) :: contact
    real(dp), intent(in) :: u(:), du(:), reaction(:)
    logical, intent(out) :: changed
    real(dp), intent(out) :: fraction
    real(dp) :: start, finish, force_scale
    integer :: i, node
    changed = .false.
    fraction = 1.0_dp
    force_scale = 0.0_dp
    do i = 1, size(contact%candidates)
      node = contact%candidates(i)
      if (contact%active(node)) force_scale = max(force_scale, abs(reaction(node_dof(deck%mesh, node, 2))))
    end do
    do i = 1, size(contact%candidates)
      node = contact%candidates(i)
      if (contact%active(node)) then
        if (.not. contact%release .or. contact%touched(node)) cycle
        if (reaction(node_dof(deck%mesh, node, 2)) < -1.0e-9_dp*force_scale) then
          contact%active(node) = .false.
          contact%let_go(node) = .true.
          changed = .true.
        end if
      else
        if (contact%let_go(node)) cycle
        finish = contact_gap(deck, contact, u, node) + du(node_dof(deck%mesh, node, 2))
        if (finish >= -contact%tolerance) cycle
        start = max(contact_gap(deck, contact, u, node), 0.0_dp)
        fraction = min(fraction, start/(start - finish))
        contact%active(node) = .true.
        contact%touched(node) = .true.
        changed = .true.
      end if
    end do
    if (changed) contact%iterations = contact%iterations + 1
  end subroutine contact_search

  !> Number of contact nodes.
  pure integer function contact_count(contact) result(number)
    type(contact_t), intent(in) :: contact
    number = 0
    if (allocated(contact%active)) number = count(contact%active)
  end function contact_count

  !> Total plate force (N; N/m in plane strain): 2 pi times the sum of the
  !> z reactions per radian of the contact nodes (positive: the plate pushes).
  pure real(dp) function contact_force(deck, contact, reaction) result(force)
    type(deck_t), intent(in) :: deck
    type(contact_t), intent(in) :: contact
    real(dp), intent(in) :: reaction(:)
    integer :: i, node
    force = 0.0_dp
    do i = 1, size(contact%candidates)
      node = contact%candidates(i)
      if (contact%active(node)) force = force + reaction(node_dof(deck%mesh, node, 2))
    end do
    if (deck%geometry == geometry_axisymmetric) force = 2.0_dp*pi*force
  end function contact_force

  !> Contact radius: the largest |r| of a contact node in the undeformed body
  !> (the frame of the small-displacement theory, and of Hertz's a); 0 without contact.
  pure real(dp) function contact_radius(deck, contact) result(radius)
    type(deck_t), intent(in) :: deck
    type(contact_t), intent(in) :: contact
    integer :: i, node
    radius = 0.0_dp
    do i = 1, size(contact%candidates)
      node = contact%candidates(i)
      if (contact%active(node)) radius = max(radius, abs(deck%mesh%xy(1, node)))
    end do
  end function contact_radius

  !> The free candidate nearest the plate (0 if none): the paper's "non-contact
  !> node nearest to the contact nodes", whose velocity reversal marks maximum deformation.
  pure integer function nearest_free_node(deck, contact, u) result(nearest)
    type(deck_t), intent(in) :: deck
    type(contact_t), intent(in) :: contact
    real(dp), intent(in) :: u(:)
    integer :: i, node
    real(dp) :: gap, best
    nearest = 0
    best = huge(1.0_dp)
    do i = 1, size(contact%candidates)
      node = contact%candidates(i)
      if (contact%active(node)) cycle
      gap = contact_gap(deck, contact, u, node)
      if (gap < best) then
        best = gap
        nearest = node
      end if
    end do
  end function nearest_free_node

  !> The contact pressure p (Pa, per node; 0 off contact) recovered from the z
  !> reactions R (per radian) of the contact nodes by a boundary-mass
  !> projection, lumped by rows: p_i = R_i / A_i with
  !>   A_i = sum_j M_ij = int N_i r ds    (r = 1 in plane strain)
  !> over the undeformed edges whose two nodes are in contact (a contact node
  !> with no such edge, e.g. the pole alone, takes all its boundary edges).
  !> Undeformed, because the reactions come from the small-displacement
  !> stiffness of the undeformed body (on the deformed edges a uniform p
  !> would come back as p/(1 + nu p/E)^2).
  !> A uniform pressure is recovered exactly: on the axis node of an edge of
  !> length h, A = h^2/6 per radian (the naive tributary disc r < h/2 gives
  !> h^2/8 and overstates q by 4/3). The consistent (unlumped) projection
  !> M p = R is not used: when the true contact edge lies between the last
  !> contact node and the next free one, it oscillates (on the level-2
  !> sphere of Table 1 the pole pressure even turns negative). q = p at the pole.
  subroutine contact_pressure(deck, contact, reaction, pressure, q)
    type(deck_t), intent(in) :: deck
    type(contact_t), intent(in) :: contact
    real(dp), intent(in) :: reaction(:)
    real(dp), intent(out) :: pressure(:)
    real(dp), intent(out) :: q
    real(dp), allocatable :: area(:)
    logical, allocatable :: has_edge(:)
    integer :: k, a, b, i, node
    real(dp) :: ra, rb, length, share_a, share_b
    pressure = 0.0_dp
    q = 0.0_dp
    associate (mesh => deck%mesh)
    if (.not. any(contact%active)) return
    allocate(area(mesh%nnode), has_edge(mesh%nnode))
    area = 0.0_dp
    has_edge = .false.
    do k = 1, size(contact%edges, 2)
      a = contact%edges(1, k)
      b = contact%edges(2, k)
      if (contact%active(a) .and. contact%active(b)) then
        has_edge(a) = .true.
        has_edge(b) = .true.
      end if
    end do
    do k = 1, size(contact%edges, 2)
      a = contact%edges(1, k)
      b = contact%edges(2, k)
      if (.not. (contact%active(a) .or. contact%active(b))) cycle
      ra = abs(mesh%xy(1, a))
      rb = abs(mesh%xy(1, b))
      length = norm2(mesh%xy(:, a) - mesh%xy(:, b))
      if (deck%geometry == geometry_axisymmetric) then     ! int N_a r ds, int N_b r ds
        share_a = length*(2.0_dp*ra + rb)/6.0_dp
        share_b = length*(ra + 2.0_dp*rb)/6.0_dp
      else
        share_a = 0.5_dp*length
        share_b = 0.5_dp*length
      end if
      if (contact%active(a) .and. contact%active(b)) then
        area(a) = area(a) + share_a
        area(b) = area(b) + share_b
      else if (contact%active(a) .and. .not. has_edge(a)) then
        area(a) = area(a) + share_a
      else if (contact%active(b) .and. .not. has_edge(b)) then
        area(b) = area(b) + share_b
      end if
    end do
    do i = 1, size(contact%candidates)
      node = contact%candidates(i)
      if (contact%active(node) .and. area(node) > 0.0_dp) &
        pressure(node) = reaction(node_dof(mesh, node, 2))/area(node)
    end do
    q = pressure(contact%pole)
    end associate
  end subroutine contact_pressure

  !> Volume row sums int N_i dV per equation (per radian in axisymmetry):
  !> the weights of a volume (or, times rho, mass) average of a nodal field.
  function volume_weights(deck) result(weight)
    type(deck_t), intent(in) :: deck
    real(dp) :: weight(2*deck%mesh%nnode)
    real(dp) :: m(4)
    integer :: e
    weight = 0.0_dp
    do e = 1, deck%mesh%nelem
      m = element_lumped_mass(deck%geometry, deck%mesh%xy(:, deck%mesh%connectivity(:, e)), 1.0_dp)
      call scatter_add(deck%mesh, e, [m(1), m(1), m(2), m(2), m(3), m(3), m(4), m(4)], weight)
    end do
  end function volume_weights

  !> STATIC with a PLATE: the body pressed onto the plate (loads, gravity,
  !> prescribed support displacements), followed as the load grows from 0 to
  !> its full value (load factor lambda). While the contact set stands the
  !> response is linear in lambda, u = u_0 + lambda u_1, so the path is
  !> followed exactly: the set changes at the smallest lambda at which a free
  !> node reaches the plate or a contact node's z reaction reaches zero.
  !>
  !> A node that reaches the plate is put on it where it is: u_z = Z - z and,
  !> with STICK, u_r = its u_r at that moment (it keeps the tangential
  !> position it touched at, as in the dynamic STICK: the incremental no-slip
  !> contact of Mossakovskii and Spence). A contact node is freed only when
  !> its reaction turns tensile (whatever RELEASE says: a static contact set
  !> must push everywhere). A stuck node freed at some lambda that goes
  !> through the plate at the same lambda slides from then on (u_z held, u_r
  !> free): at zero normal force it can carry no tangential force, and with
  !> u_z alone held the reaction and the approach of a node have opposite
  !> signs, so it cannot alternate between pulling and going through.
  !>
  !> With SLIP this is the path of frictionless contact, whose end is the one
  !> set in which every contact node pushes and no free node is through the
  !> plate. (Holding a STICK node at u_r = 0, where it was before the load,
  !> is what a one-shot iteration does; the edge nodes then pull when held
  !> and go through the plate when freed, and the set never settles.)
  subroutine solve_static_contact(deck, record, error)
    type(deck_t), intent(in) :: deck
    type(record_t), intent(inout) :: record
    type(error_t), allocatable, intent(out) :: error
    type(contact_t) :: contact
    type(static_solution_t) :: solution
    type(static_path_t) :: path
    real(dp), allocatable :: u(:), reaction(:), pressure(:), weight(:)
    logical, allocatable :: held(:)
    real(dp) :: q, surface(4)

    associate (mesh => deck%mesh)
    call contact_create(deck, contact)
    call follow_static_path(deck, contact, path, error)
    if (allocated(error)) return
    ! The final state, solved again from the final set for its stresses.
    held = static_held(deck, contact, path%state)
    call solve_static(deck, solution, error, held, path%values)
    if (allocated(error)) return
    u = band_vector(mesh, solution%displacement)
    reaction = band_vector(mesh, solution%reaction)
    if (.not. (all(ieee_is_finite(u)) .and. all(ieee_is_finite(reaction)) .and. all(ieee_is_finite(solution%stress)))) then
      call set_error(error, not_finite_message, file=deck%cards%file)
      return
    end if
    call check_settled(deck, contact, u, reaction, error)
    if (allocated(error)) return
    call static_record(deck, solution, record)
    call bruise_static(deck, solution%stress, solution%strain, record)
    allocate(pressure(mesh%nnode))
    call contact_pressure(deck, contact, reaction, pressure, q)
    weight = volume_weights(deck)
    call record_put_integer(record, 'factorizations', path%solves + 1)
    call record_put_integer(record, 'contact_iterations', contact%iterations)
    call record_put_integer(record, 'contact_nodes', contact_count(contact))
    if (contact%stick) call record_put_integer(record, 'contact_sliding_nodes', count(path%state == node_sliding))
    call record_put_real(record, 'force_N', contact_force(deck, contact, reaction))
    call record_put_real(record, 'alpha_mm', -1.0e3_dp*dot_product(weight(2::2), u(2::2))/sum(weight(2::2)))
    call record_put_real(record, 'q_MPa', 1.0e-6_dp*q)
    surface = node_stress(mesh, solution%stress, contact%pole)
    call record_put_real(record, 'q_surface_MPa', -1.0e-6_dp*surface(2))
    call record_put_real(record, 'contact_radius_mm', 1.0e3_dp*contact_radius(deck, contact))
    end associate
  end subroutine solve_static_contact

  !> The static contact path (solve_static_contact) from lambda = 0 to 1:
  !> the final contact set in contact%active and path%state, the held values in path%values.
  subroutine follow_static_path(deck, contact, path, error)
    type(deck_t), intent(in) :: deck
    type(contact_t), intent(inout) :: contact
    type(static_path_t), intent(out) :: path
    type(error_t), allocatable, intent(out) :: error
    type(held_system_t) :: system
    logical, allocatable :: held(:)
    real(dp), allocatable :: change_at(:)
    real(dp) :: next
    integer :: i, node, limit, event

    associate (mesh => deck%mesh)
    allocate(path%state(mesh%nnode), path%changes(mesh%nnode), path%freed_here(mesh%nnode), &
             path%values(2*mesh%nnode), path%base(2*mesh%nnode), path%rate(2*mesh%nnode))
    path%state = node_free
    path%values = 0.0_dp
    path%base = 0.0_dp
    path%rate = 0.0_dp
    path%changes = 0
    path%freed_here = .false.
    do i = 1, size(contact%candidates)
      node = contact%candidates(i)
      if (mesh%xy(2, node) - contact%z_plate <= contact%tolerance) call path_touch(deck, contact, path, node)
    end do
    call held_system_create(deck, system)
    limit = 50 + 10*size(contact%candidates)
    do event = 1, limit
      held = static_held(deck, contact, path%state)
      call held_system_solve(deck, system, held, path%values, path%base, path%rate, path%reaction_base, &
                             path%reaction_rate, error)
      path%solves = path%solves + 1
      if (allocated(error)) then
        error%message = error%message//' (with '//itoa(count(contact%active))//' node(s) on the plate at '// &
          gtoa(100.0_dp*path%load_factor)//' % of the load: a body that only rests on the plate needs a load '// &
          'that presses it on, and supports that stop it from turning or sliding)'
        if (error%line == 0) then                       ! located at the PLATE card, which holds the body
          error%line = deck%plate%line
          error%card = 'PLATE'
        end if
        return
      end if
      if (.not. (all(ieee_is_finite(path%base)) .and. all(ieee_is_finite(path%rate)) .and. &
                 all(ieee_is_finite(path%reaction_base)) .and. all(ieee_is_finite(path%reaction_rate)))) then
        call set_error(error, not_finite_message, file=deck%cards%file)
        return
      end if
      change_at = change_factors(deck, contact, path)
      next = minval(change_at)
      if (next > 1.0_dp) return                         ! the set stands to the full load
      if (next > path%load_factor + same_factor) then   ! moving on along the path
        path%load_factor = next
        path%changes = 0
        path%freed_here = .false.
        path%best_violations = huge(1)
        path%strikes = 0
        call apply_changes(deck, contact, path, change_at <= next + same_factor)
      else                                              ! again at the same load factor
        call apply_changes(deck, contact, path, immediate_changes(deck, contact, path, change_at))
      end if
      contact%iterations = contact%iterations + 1
    end do
    node = maxloc(path%changes, dim=1)
    call set_error(error, 'the contact set did not settle after '//itoa(limit)//' changes: at '// &
      gtoa(100.0_dp*path%load_factor)//' % of the load, node '//itoa(mesh%node_id(node))//' (r = '// &
      gtoa(1.0e3_dp*mesh%xy(1, node))//' mm) went '//itoa(path%changes(node))//' times between free and held '// &
      '(it pulls on the plate when held and goes through it when free)'//slip_hint(contact), &
      file=deck%cards%file, line=deck%plate%line, card='PLATE')
    end associate
  end subroutine follow_static_path

  !> The advice that ends a STICK contact error.
  pure function slip_hint(contact) result(text)
    type(contact_t), intent(in) :: contact
    character(:), allocatable :: text
    text = ''
    if (contact%stick) text = ' (frictionless contact, PLATE ... SLIP, always settles)'
  end function slip_hint

  !> Per node, the load factor in [lambda, 1] at which the current set stops
  !> holding for it (huge if it holds to the full load): a free node reaches
  !> the plate (its gap at lambda = 1 is below -tolerance), a contact node's
  !> z reaction reaches zero (it is tensile at lambda = 1). Both are linear
  !> in the load factor; lambda itself if the node is already past it.
  function change_factors(deck, contact, path) result(factor)
    type(deck_t), intent(in) :: deck
    type(contact_t), intent(in) :: contact
    type(static_path_t), intent(in) :: path
    real(dp) :: factor(deck%mesh%nnode)
    real(dp) :: now, last, small
    integer :: i, node, z
    factor = huge(1.0_dp)
    small = reaction_tolerance(deck, contact, path)
    associate (lambda => path%load_factor)
    do i = 1, size(contact%candidates)
      node = contact%candidates(i)
      z = node_dof(deck%mesh, node, 2)
      if (path%state(node) == node_free) then
        now = contact_gap(deck, contact, path%base + lambda*path%rate, node)
        last = contact_gap(deck, contact, path%base + path%rate, node)
        if (last >= -contact%tolerance) cycle
        factor(node) = lambda
        if (now > contact%tolerance) factor(node) = lambda + (1.0_dp - lambda)*now/(now - last)
      else
        now = path%reaction_base(z) + lambda*path%reaction_rate(z)
        last = path%reaction_base(z) + path%reaction_rate(z)
        if (last >= -small) cycle
        factor(node) = lambda
        if (now > small) factor(node) = lambda + (1.0_dp - lambda)*now/(now - last)
      end if
    end do
    end associate
  end function change_factors

  !> Round-off level of the z reactions of the path (N per radian): 1e-9 of the largest.
  real(dp) function reaction_tolerance(deck, contact, path) result(small)
    type(deck_t), intent(in) :: deck
    type(contact_t), intent(in) :: contact
    type(static_path_t), intent(in) :: path
    integer :: i, z
    small = 0.0_dp
    do i = 1, size(contact%candidates)
      if (.not. contact%active(contact%candidates(i))) cycle
      z = node_dof(deck%mesh, contact%candidates(i), 2)
      small = max(small, abs(path%reaction_base(z) + path%reaction_rate(z)), &
                  abs(path%reaction_base(z) + path%load_factor*path%reaction_rate(z)))
    end do
    small = 1.0e-9_dp*small
  end function reaction_tolerance

  !> The changes to make at the same load factor again (the state is past a
  !> limit there: at a degenerate point where several nodes have zero gap
  !> and zero force, such as a flat face resting on the plate at lambda = 0,
  !> or after a freed stuck node's tangential reaction is gone). The block
  !> principal pivoting of Judice and Pires: every node past its limit
  !> changes at once while that lowers the count of such nodes below its
  !> best at this load factor, or has not failed to for `strikes_allowed`
  !> changes; otherwise only the first such node in candidate order changes
  !> (Murty's least-index rule), until the count is below its best again.
  !> That ends for the frictionless problem, whose held z equations have a
  !> positive definite Schur complement (a P-matrix complementarity
  !> problem); block pivoting alone can cycle, the least-index rule alone is
  !> slow (over 300 changes for a strip of 39 bottom nodes lifted at one end,
  !> where the one-shot iteration needed 28; with 10 strikes at most 48 over
  !> 200 random lifted strips and discs).
  function immediate_changes(deck, contact, path, change_at) result(due)
    type(deck_t), intent(in) :: deck
    type(contact_t), intent(in) :: contact
    type(static_path_t), intent(inout) :: path
    real(dp), intent(in) :: change_at(:)
    logical :: due(deck%mesh%nnode)
    integer :: i, node, violations
    due = change_at <= path%load_factor + same_factor
    violations = count(due)
    if (violations < path%best_violations) then
      path%best_violations = violations
      path%strikes = 0
      return
    end if
    path%strikes = path%strikes + 1
    if (path%strikes <= strikes_allowed) return
    due = .false.
    do i = 1, size(contact%candidates)
      node = contact%candidates(i)
      if (change_at(node) > path%load_factor + same_factor) cycle
      due(node) = .true.
      return
    end do
  end function immediate_changes

  !> Change the state of the `due` nodes at path%load_factor: a free node is
  !> put on the plate, a contact node is freed.
  subroutine apply_changes(deck, contact, path, due)
    type(deck_t), intent(in) :: deck
    type(contact_t), intent(inout) :: contact
    type(static_path_t), intent(inout) :: path
    logical, intent(in) :: due(:)
    integer :: i, node
    do i = 1, size(contact%candidates)
      node = contact%candidates(i)
      if (.not. due(node)) cycle
      path%changes(node) = path%changes(node) + 1
      if (path%state(node) == node_free) then
        call path_touch(deck, contact, path, node)
      else
        path%freed_here(node) = path%freed_here(node) .or. path%state(node) == node_stuck
        path%state(node) = node_free
        contact%active(node) = .false.
      end if
    end do
  end subroutine apply_changes

  !> Put a node on the plate where the path has it: u_z = Z - z; with STICK
  !> also u_r held at its present value, unless the node was freed from
  !> sticking at this load factor (then it slides).
  subroutine path_touch(deck, contact, path, node)
    type(deck_t), intent(in) :: deck
    type(contact_t), intent(inout) :: contact
    type(static_path_t), intent(inout) :: path
    integer, intent(in) :: node
    integer :: r
    contact%active(node) = .true.
    path%values(node_dof(deck%mesh, node, 2)) = contact%z_plate - deck%mesh%xy(2, node)
    path%state(node) = node_sliding
    if (.not. contact%stick .or. path%freed_here(node)) return
    path%state(node) = node_stuck
    r = node_dof(deck%mesh, node, 1)
    path%values(r) = path%base(r) + path%load_factor*path%rate(r)
  end subroutine path_touch

  !> The equations held by the plate on the static path: u_z of every contact
  !> node, u_r of the stuck ones.
  function static_held(deck, contact, state) result(held)
    type(deck_t), intent(in) :: deck
    type(contact_t), intent(in) :: contact
    integer, intent(in) :: state(:)
    logical :: held(2*deck%mesh%nnode)
    integer :: i, node
    held = .false.
    do i = 1, size(contact%candidates)
      node = contact%candidates(i)
      if (state(node) == node_free) cycle
      held(node_dof(deck%mesh, node, 2)) = .true.
      if (state(node) == node_stuck) held(node_dof(deck%mesh, node, 1)) = .true.
    end do
  end function static_held

  !> The stiffness S and the full load R (loads and gravity) of a static
  !> contact problem, assembled once for the whole path.
  subroutine held_system_create(deck, system)
    type(deck_t), intent(in) :: deck
    type(held_system_t), intent(out) :: system
    real(dp), allocatable :: shear(:), bulk(:)
    shear = deck%materials(deck%mesh%element_material)%shear
    bulk = deck%materials(deck%mesh%element_material)%bulk
    call assemble_stiffness(deck, shear, bulk, system%stiffness)
    system%load = external_load(deck, 0.0_dp) + gravity_load(deck)
    system%supports = support_mask(deck)
    system%prescribed = prescribed_displacement(deck, 0.0_dp)
  end subroutine held_system_create

  !> With the supports and the `held` equations fixed: u_1, the response to
  !> the full load and prescribed support displacements (held values 0), and
  !> u_0, the response to the held values alone (no load), with their
  !> reactions S u - R. The state at load factor lambda is u_0 + lambda u_1.
  subroutine held_system_solve(deck, system, held, values, base, rate, reaction_base, reaction_rate, error)
    type(deck_t), intent(in) :: deck
    type(held_system_t), intent(in) :: system
    logical, intent(in) :: held(:)
    real(dp), intent(in) :: values(:)
    real(dp), allocatable, intent(out) :: base(:), rate(:), reaction_base(:), reaction_rate(:)
    type(error_t), allocatable, intent(out) :: error
    type(band_matrix_t) :: factor
    real(dp), allocatable :: rhs(:, :)
    logical, allocatable :: fixed(:)
    integer :: info
    fixed = system%supports .or. held
    factor = system%stiffness
    call band_constrain_matrix(factor, fixed)
    call band_factor(factor, info)
    if (info > 0) then
      call set_error(error, singular_message(deck, info), file=deck%cards%file)
      return
    end if
    allocate(rhs(size(values), 2))
    rhs(:, 1) = system%load
    call band_constrain_rhs(system%stiffness, fixed, merge(0.0_dp, system%prescribed, held), rhs(:, 1))
    rhs(:, 2) = 0.0_dp
    call band_constrain_rhs(system%stiffness, fixed, merge(values, 0.0_dp, held), rhs(:, 2))
    call band_solve_many(factor, rhs)
    rate = rhs(:, 1)
    base = rhs(:, 2)
    reaction_rate = band_multiply(system%stiffness, rate) - system%load
    reaction_base = band_multiply(system%stiffness, base)
  end subroutine held_system_solve

  !> The final static state must be one in which no free node is through the
  !> plate (beyond the tolerance) and every contact node pushes (to round-off).
  subroutine check_settled(deck, contact, u, reaction, error)
    type(deck_t), intent(in) :: deck
    type(contact_t), intent(in) :: contact
    real(dp), intent(in) :: u(:), reaction(:)
    type(error_t), allocatable, intent(out) :: error
    real(dp) :: small
    integer :: i, node, z
    small = 0.0_dp
    do i = 1, size(contact%candidates)
      node = contact%candidates(i)
      if (contact%active(node)) small = max(small, abs(reaction(node_dof(deck%mesh, node, 2))))
    end do
    small = 1.0e-6_dp*small
    do i = 1, size(contact%candidates)
      node = contact%candidates(i)
      z = node_dof(deck%mesh, node, 2)
      if ((contact%active(node) .and. reaction(z) < -small) .or. &
          (.not. contact%active(node) .and. contact_gap(deck, contact, u, node) < -contact%tolerance)) then
        call set_error(error, 'the static contact state is not admissible at node '//itoa(deck%mesh%node_id(node))// &
          ' (r = '//gtoa(1.0e3_dp*deck%mesh%xy(1, node))//' mm): '//trim(merge('it pulls on the plate     ', &
          'it is through the plate   ', contact%active(node))), file=deck%cards%file, line=deck%plate%line, card='PLATE')
        return
      end if
    end do
  end subroutine check_settled
end module visco2d_contact
