!> The contact extension: a rigid flat plate z = Z that the body may touch
!> (the paper's "Numerical Procedure"). The plate is fixed. A boundary node
!> that reaches it gets an adjusted-displacement condition (it is put on the
!> plate) and the same increment is repeated; from then on it is held:
!> STICK holds u_r and u_z, SLIP (frictionless) u_z only. With RELEASE=YES a
!> contact node whose reaction turns tensile is freed again.
!>
!> With a PAD (visco2d_pad_mesh) the body touches the pad's top surface
!> instead: node to segment, each body node against the pad surface segment
!> under its undeformed r (the small-displacement frame; with KINEMATICS
!> LARGE under its current r, pair_on_surface, at every step), with weights
!> (1 - s, s) on the segment's two nodes. Its gap is then
!>   g = z + u_z - Z - [(1 - s) u_z(a) + s u_z(b)],
!> and a held node keeps g = 0 (and, with STICK, the same relation in u_r):
!> a multi-point constraint that visco2d_capacitance imposes with equal and
!> opposite forces on the body node and the segment.
!>
!> With a second BODY (visco2d_body_mesh) the surface under the first body
!> is the second body's upper surface, curved: the same node-to-segment
!> constraint, with the gap measured from the undeformed surface under the
!> node, z_s = (1 - s) z(a) + s z(b), instead of Z:
!>   g = z + u_z - z_s - [(1 - s) u_z(a) + s u_z(b)].
!> In the small-displacement frame of the module (each node against the
!> segment under its undeformed r) this is the gap of two spheres head on,
!> g ~ r^2/(2 R*) near the axis, 1/R* = 1/R1 + 1/R2.
!>
!> This module holds the contact state and search used by the dynamics, and
!> the contact pressure recovered from the nodal reactions (a consistent
!> boundary-mass projection), the contact radius and force. The static
!> indentation solver (STATIC with a PLATE) is visco2d_static_contact; the
!> Hertz reference, eqs. [43]-[45], is visco2d_hertz (hertz_t and
!> hertz_impact are re-exported here).
module visco2d_contact
  use visco2d_kinds, only: dp, pi, geometry_axisymmetric, geometry_tolerance
  use visco2d_deck, only: deck_t
  use visco2d_mesh, only: boundary_sides
  use visco2d_assembly, only: node_dof, support_mask
  use visco2d_capacitance, only: constraint_sum
  use visco2d_hertz, only: hertz_t, hertz_impact
  use visco2d_pad_mesh, only: body_elements
  implicit none
  private

  public :: contact_t, hertz_t
  public :: contact_create, contact_held_dofs, contact_begin_increment, contact_search, contact_count
  public :: contact_release_tensile, pair_on_surface
  public :: contact_pressure, contact_force, contact_radius, contact_gap, nearest_free_node
  public :: hertz_impact, contact_partner_sum, pad_compression

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
    logical :: pad = .false.                    !< the body touches a pad's surface, not the rigid plate
    !> (2, equations) by equation of a body node that may touch a pad: the pad
    !> surface equations under the node in the same direction (0: none, or
    !> supported), and their weights (1 - s, s): the other end of its
    !> constraint. All 0 on the rigid plate.
    integer, allocatable :: partner(:, :)
    real(dp), allocatable :: weight(:, :)
    integer :: pad_axis = 0                     !< the pad's surface node on the axis (its compression)
    !> (nnode) the undeformed z of the surface under each node, from which its gap is
    !> measured: Z (the plate's, or the pad's top) everywhere, except under a second BODY
    real(dp), allocatable :: surface_z(:)
    logical :: body = .false.                   !< the surface is a second BODY's (curved, free)
    integer :: iterations = 0                   !< increments repeated because the contact set changed
  end type contact_t

contains

  !> The candidate nodes and edges (element sides that belong to one element
  !> only, except those on the axis r = 0 of an axisymmetric body), the plate,
  !> and the nodes that start on it.
  subroutine contact_create(deck, contact)
    type(deck_t), intent(in) :: deck
    type(contact_t), intent(out) :: contact
    integer, allocatable :: sides(:, :)
    logical, allocatable :: boundary(:)
    integer :: a, b, i, nedge
    associate (mesh => deck%mesh)
    contact%z_plate = deck%plate%z
    contact%stick = deck%plate%stick
    contact%release = deck%plate%release
    if (deck%body%line > 0) then                      ! two free bodies: the BODY card's contact kind
      contact%stick = deck%body%stick
      contact%release = deck%body%release
    end if
    contact%tolerance = geometry_tolerance*mesh%size
    sides = boundary_sides(mesh, body_elements(deck))   ! the body's: a pad is what it touches
    allocate(contact%edges(2, size(sides, 2)), boundary(mesh%nnode))
    boundary = .false.
    nedge = 0
    do i = 1, size(sides, 2)
      a = sides(1, i)
      b = sides(2, i)
      if (deck%settings%geometry == geometry_axisymmetric .and. mesh%xy(1, a) == 0.0_dp .and. &
          mesh%xy(1, b) == 0.0_dp) cycle
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
    allocate(contact%partner(2, 2*mesh%nnode), contact%weight(2, 2*mesh%nnode))
    contact%partner = 0
    contact%weight = 0.0_dp
    contact%surface_z = spread(contact%z_plate, 1, mesh%nnode)
    end associate
    if (deck%pad%first_node > 0) call pad_partners(deck, contact)
    if (deck%body%line > 0) call body_surface_heights(deck, contact)
  end subroutine contact_create

  !> Under each candidate, the pad surface segment that contains its
  !> undeformed r: the partner equations and weights of the node's r and z
  !> equations (none beyond the pad's width; a supported equation has none,
  !> and supported partners are left out: they do not move).
  subroutine pad_partners(deck, contact)
    type(deck_t), intent(in) :: deck
    type(contact_t), intent(inout) :: contact
    real(dp), allocatable :: u(:)
    logical :: changed
    contact%pad = .true.
    contact%pad_axis = deck%pad%surface(1)
    allocate(u(2*deck%mesh%nnode))
    u = 0.0_dp
    call pair_on_surface(deck, contact, u, 0.0_dp, changed)
  end subroutine pad_partners

  !> Each candidate against the pad surface segment under its current radius
  !> |r + u_r|, the surface nodes at theirs, with the weights of the current
  !> positions; `tolerance` > 0 keeps a pairing whose segment is the same and
  !> whose s moved by at most that; `changed`: some pairing changed.
  subroutine pair_on_surface(deck, contact, u, tolerance, changed)
    type(deck_t), intent(in) :: deck
    type(contact_t), intent(inout) :: contact
    real(dp), intent(in) :: u(:)
    real(dp), intent(in) :: tolerance
    logical, intent(out) :: changed
    logical, allocatable :: supports(:)
    real(dp), allocatable :: surface_radius(:)
    integer :: i, k, node, c, j, equation, other, found
    real(dp) :: r, s, old_s
    associate (mesh => deck%mesh, surface => deck%pad%surface)
    changed = .false.
    supports = support_mask(deck%mesh, deck%settings, deck%loads)
    allocate(surface_radius(size(surface)))
    do k = 1, size(surface)
      surface_radius(k) = abs(mesh%xy(1, surface(k)) + u(node_dof(mesh, surface(k), 1)))
    end do
    do i = 1, size(contact%candidates)
      node = contact%candidates(i)
      r = abs(mesh%xy(1, node) + u(node_dof(mesh, node, 1)))
      found = 0
      do k = 1, size(surface) - 1
        if (r > surface_radius(k + 1)) cycle
        found = k
        exit
      end do
      s = 0.0_dp
      if (found > 0) s = max(0.0_dp, (r - surface_radius(found))/(surface_radius(found + 1) - surface_radius(found)))
      do c = 1, 2
        equation = node_dof(mesh, node, c)
        if (supports(equation)) cycle
        if (tolerance > 0.0_dp .and. found > 0) then
          old_s = contact%weight(2, equation)
          if (contact%partner(1, equation) == node_dof(mesh, surface(found), c) .and. &
              contact%partner(2, equation) == node_dof(mesh, surface(found + 1), c) .and. &
              abs(s - old_s) <= tolerance) cycle
        end if
        if (found == 0 .and. all(contact%partner(:, equation) == 0)) cycle
        changed = .true.
        contact%partner(:, equation) = 0
        contact%weight(:, equation) = 0.0_dp
        if (found == 0) cycle
        do j = 1, 2
          other = node_dof(mesh, surface(found + j - 1), c)
          if (supports(other)) cycle
          contact%partner(j, equation) = other
          contact%weight(j, equation) = merge(1.0_dp - s, s, j == 1)
        end do
      end do
    end do
    end associate
    if (changed .and. contact%body) call body_surface_heights(deck, contact)   ! the curved surface under the new s
  end subroutine pair_on_surface

  !> Under a second BODY: the undeformed z of its surface under each
  !> candidate, (1 - s) z(a) + s z(b) on the segment that contact%partner
  !> names (with the weights (1 - s, s) of the z equation).
  subroutine body_surface_heights(deck, contact)
    type(deck_t), intent(in) :: deck
    type(contact_t), intent(inout) :: contact
    integer, allocatable :: node_of(:)
    integer :: i, k, node, equation
    contact%body = .true.
    allocate(node_of(deck%mesh%nnode))
    node_of(deck%mesh%equation) = [(i, i = 1, deck%mesh%nnode)]    ! band position -> node
    do i = 1, size(contact%candidates)
      node = contact%candidates(i)
      equation = node_dof(deck%mesh, node, 2)
      if (contact%partner(1, equation) == 0) cycle            ! beyond the second body's surface
      contact%surface_z(node) = 0.0_dp
      do k = 1, 2
        if (contact%partner(k, equation) > 0) contact%surface_z(node) = contact%surface_z(node) + &
          contact%weight(k, equation)*deck%mesh%xy(2, node_of((contact%partner(k, equation) + 1)/2))
      end do
    end do
  end subroutine body_surface_heights

  !> sum_k w_k f(partner_k) for component `component` (1: r, 2: z) of the
  !> nodal field f (band order): the pad surface's value under a body node
  !> (0 for the rigid plate, or a node beyond the pad).
  pure real(dp) function contact_partner_sum(deck, contact, field, node, component) result(total)
    type(deck_t), intent(in) :: deck
    type(contact_t), intent(in) :: contact
    real(dp), intent(in) :: field(:)
    integer, intent(in) :: node, component
    total = constraint_sum(contact%partner, contact%weight, field, node_dof(deck%mesh, node, component))
  end function contact_partner_sum

  !> The pad's compression at the axis, -u_z of its surface there (m; 0 without a pad).
  pure real(dp) function pad_compression(deck, contact, u) result(compression)
    type(deck_t), intent(in) :: deck
    type(contact_t), intent(in) :: contact
    real(dp), intent(in) :: u(:)
    compression = 0.0_dp
    if (contact%pad) compression = -u(node_dof(deck%mesh, contact%pad_axis, 2))
  end function pad_compression

  !> Gap z + u_z - Z of a node (m), u the displacement vector in band order;
  !> with a pad, less the pad surface's u_z under the node (huge beyond the pad).
  pure real(dp) function contact_gap(deck, contact, u, node) result(gap)
    type(deck_t), intent(in) :: deck
    type(contact_t), intent(in) :: contact
    real(dp), intent(in) :: u(:)
    integer, intent(in) :: node
    gap = deck%mesh%xy(2, node) + u(node_dof(deck%mesh, node, 2)) - contact%surface_z(node)
    if (.not. contact%pad) return
    if (contact%partner(1, node_dof(deck%mesh, node, 2)) == 0) then     ! beyond the pad
      gap = huge(1.0_dp)
    else
      gap = gap - contact_partner_sum(deck, contact, u, node, 2)
    end if
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
  !> plate reaction (z, per radian) is tensile (on a PAD that is done at the
  !> start of the increment instead, contact_release_tensile). A node
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
    force_scale = largest_reaction(deck, contact, reaction)
    do i = 1, size(contact%candidates)
      node = contact%candidates(i)
      if (contact%active(node)) then
        if (.not. contact%release .or. contact%touched(node) .or. contact%pad) cycle
        if (is_tensile(reaction(node_dof(deck%mesh, node, 2)), force_scale)) then
          contact%active(node) = .false.
          contact%let_go(node) = .true.
          changed = .true.
        end if
      else
        if (contact%let_go(node)) cycle
        finish = contact_gap(deck, contact, u, node) + du(node_dof(deck%mesh, node, 2)) &
                 - contact_partner_sum(deck, contact, du, node, 2)
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

  !> On a PAD with RELEASE=YES, at the start of an increment: free every
  !> contact node whose reaction (z, per radian) at the end of the last
  !> increment was tensile. contact_search does not free pad nodes within
  !> the increment: freeing a pair whose last force was compressive lets
  !> that force work on the pair's separation over the step (the
  !> trapezoidal work 1/2 lambda_t dg of the integrators), energy the
  !> contact does not have; after release on a tensile force that work
  !> is negative. A pair thus holds a tension for at most one increment.
  !> The node may touch again in the same increment (contact_search).
  subroutine contact_release_tensile(deck, contact, reaction, changed)
    type(deck_t), intent(in) :: deck
    type(contact_t), intent(inout) :: contact
    real(dp), intent(in) :: reaction(:)
    logical, intent(out) :: changed
    real(dp) :: force_scale
    integer :: i, node
    changed = .false.
    if (.not. (contact%pad .and. contact%release)) return
    force_scale = largest_reaction(deck, contact, reaction)
    do i = 1, size(contact%candidates)
      node = contact%candidates(i)
      if (.not. contact%active(node)) cycle
      if (is_tensile(reaction(node_dof(deck%mesh, node, 2)), force_scale)) then
        contact%active(node) = .false.
        changed = .true.
      end if
    end do
  end subroutine contact_release_tensile

  !> The largest |z reaction| of a contact node (per radian): the scale of the release test.
  pure real(dp) function largest_reaction(deck, contact, reaction) result(scale)
    type(deck_t), intent(in) :: deck
    type(contact_t), intent(in) :: contact
    real(dp), intent(in) :: reaction(:)
    integer :: i, node
    scale = 0.0_dp
    do i = 1, size(contact%candidates)
      node = contact%candidates(i)
      if (contact%active(node)) scale = max(scale, abs(reaction(node_dof(deck%mesh, node, 2))))
    end do
  end function largest_reaction

  !> The release test: a z reaction pulls, beyond round-off of the largest (1e-9 of it).
  pure logical function is_tensile(reaction, scale)
    real(dp), intent(in) :: reaction, scale
    is_tensile = reaction < -1.0e-9_dp*scale
  end function is_tensile

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
    if (deck%settings%geometry == geometry_axisymmetric) force = 2.0_dp*pi*force
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
      if (deck%settings%geometry == geometry_axisymmetric) then     ! int N_a r ds, int N_b r ds
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
end module visco2d_contact
