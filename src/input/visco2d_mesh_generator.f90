!> Mesh generators: the graded half-disc section of a sphere (the fruit grid
!> of Fig. 1) and a structured rectangle. They return raw coordinates,
!> counter-clockwise connectivity and tagged boundary edges; `visco2d_mesh_build`
!> checks and numbers them.
module visco2d_mesh_generator
  use visco2d_kinds, only: dp, pi
  implicit none
  private

  public :: sphere_grid, rectangle_grid, ring_grid, sphere_default_grade, sphere_default_core
  public :: edge_set_none, edge_set_axis, edge_set_inner, edge_set_outer, edge_set_bottom, edge_set_top
  public :: edge_set_name

  integer, parameter :: edge_set_none = 0, edge_set_axis = 1, edge_set_inner = 2, &
                        edge_set_outer = 3, edge_set_bottom = 4, edge_set_top = 5

  !> Default arc grading exponent b: theta(x) = pi (e^{bx} - 1)/(e^b - 1). With b = 2.35
  !> the level-1 arc segments grow by 26.5 % each, from 5.0 deg at the contact pole.
  real(dp), parameter :: sphere_default_grade = 2.35_dp
  !> Default radius of the core block, as a fraction of R.
  real(dp), parameter :: sphere_default_core = 0.35_dp

contains

  !> Name of an edge-set code, as written on cards.
  pure function edge_set_name(code) result(name)
    integer, intent(in) :: code
    character(:), allocatable :: name
    select case (code)
    case (edge_set_axis); name = 'AXIS'
    case (edge_set_inner); name = 'INNER'
    case (edge_set_outer); name = 'OUTER'
    case (edge_set_bottom); name = 'BOTTOM'
    case (edge_set_top); name = 'TOP'
    case default; name = 'NONE'
    end select
  end function edge_set_name

  !> Half-disc section (r >= 0) of a sphere of radius R, bottom pole at z = 0,
  !> centre at z = R. Level L has f = 2^(L-1) and:
  !>  - a polar part: 8f layers between radius core*R and R, times 10f arc segments.
  !>    On the surface the segments are graded toward the contact pole (theta = 0);
  !>    the grading fades linearly with depth into the core's boundary angles
  !>    (its bottom, side and top cover 45, 90 and 45 degrees: an O-grid);
  !>  - a core block of f x 8f elements inside radius core*R (a Coons patch whose
  !>    boundary is the innermost polar circle and the axis).
  !> Level 1: 88 elements and 106 nodes (the paper's grid size); each level has 4x the elements.
  !> Edge tags: OUTER on the sphere surface, AXIS on r = 0.
  subroutine sphere_grid(radius, level, grade, core, xy, connectivity, edge_element, edge_side, edge_set)
    real(dp), intent(in) :: radius, grade, core
    integer, intent(in) :: level
    real(dp), allocatable, intent(out) :: xy(:, :)
    integer, allocatable, intent(out) :: connectivity(:, :), edge_element(:), edge_side(:), edge_set(:)
    integer :: f, ncore_r, ncore_z, nlayer, narc, nnode, nelem, nedge
    integer :: i, j, k, s, e
    integer, allocatable :: core_id(:, :), polar_id(:, :)
    real(dp), allocatable :: theta(:), rho(:)
    real(dp) :: weight
    real(dp) :: u, v
    real(dp), allocatable :: bottom(:, :), top(:, :), left(:, :), right(:, :)

    f = 2**(level - 1)
    ncore_r = f
    ncore_z = 8*f
    nlayer = 8*f
    narc = ncore_z + 2*ncore_r
    allocate(theta(0:narc), rho(0:nlayer))
    do s = 0, narc
      if (abs(grade) < 1.0e-6_dp) then
        theta(s) = pi*real(s, dp)/narc
      else
        theta(s) = pi*(exp(grade*real(s, dp)/narc) - 1.0_dp)/(exp(grade) - 1.0_dp)
      end if
    end do
    theta(narc) = pi
    do k = 0, nlayer
      rho(k) = radius*(core + (1.0_dp - core)*real(k, dp)/nlayer)
    end do

    nnode = (ncore_r + 1)*(ncore_z + 1) + nlayer*(narc + 1)
    nelem = ncore_r*ncore_z + nlayer*narc
    allocate(xy(2, nnode), connectivity(4, nelem), core_id(0:ncore_r, 0:ncore_z), polar_id(0:nlayer, 0:narc))

    ! Numbering: core rows first, then the polar layers outward.
    s = 0
    do j = 0, ncore_z
      do i = 0, ncore_r
        s = s + 1
        core_id(i, j) = s
      end do
    end do
    do k = 1, nlayer
      do i = 0, narc
        s = s + 1
        polar_id(k, i) = s
      end do
    end do
    ! Layer 0 of the polar part is the core's boundary path.
    do s = 0, narc
      if (s <= ncore_r) then
        polar_id(0, s) = core_id(s, 0)
      else if (s <= ncore_r + ncore_z) then
        polar_id(0, s) = core_id(ncore_r, s - ncore_r)
      else
        polar_id(0, s) = core_id(narc - s, ncore_z)
      end if
    end do

    do k = 0, nlayer
      weight = real(k, dp)/nlayer               ! 0 at the core, 1 on the surface
      do s = 0, narc
        xy(:, polar_id(k, s)) = polar_point(rho(k), (1.0_dp - weight)*core_angle(s) + weight*theta(s), &
                                            s == 0 .or. s == narc)
      end do
    end do

    ! Coons patch for the core interior.
    allocate(bottom(2, 0:ncore_r), top(2, 0:ncore_r), left(2, 0:ncore_z), right(2, 0:ncore_z))
    do i = 0, ncore_r
      bottom(:, i) = xy(:, core_id(i, 0))
      top(:, i) = xy(:, core_id(i, ncore_z))
    end do
    do j = 0, ncore_z
      right(:, j) = xy(:, core_id(ncore_r, j))
      left(:, j) = [0.0_dp, radius - core*radius + 2.0_dp*core*radius*real(j, dp)/ncore_z]
    end do
    left(:, 0) = bottom(:, 0)
    left(:, ncore_z) = top(:, 0)
    do j = 1, ncore_z - 1
      v = real(j, dp)/ncore_z
      do i = 0, ncore_r - 1
        u = real(i, dp)/ncore_r
        xy(:, core_id(i, j)) = (1 - u)*left(:, j) + u*right(:, j) + (1 - v)*bottom(:, i) + v*top(:, i) &
          - ((1 - u)*(1 - v)*bottom(:, 0) + u*(1 - v)*bottom(:, ncore_r) &
             + (1 - u)*v*top(:, 0) + u*v*top(:, ncore_r))
      end do
      xy(1, core_id(0, j)) = 0.0_dp
    end do

    nedge = ncore_z + 2*nlayer + narc
    allocate(edge_element(nedge), edge_side(nedge), edge_set(nedge))
    nedge = 0
    e = 0
    do j = 0, ncore_z - 1
      do i = 0, ncore_r - 1
        e = e + 1
        connectivity(:, e) = [core_id(i, j), core_id(i + 1, j), core_id(i + 1, j + 1), core_id(i, j + 1)]
        if (i == 0) call add_edge(e, 4, edge_set_axis)
      end do
    end do
    do k = 0, nlayer - 1
      do s = 0, narc - 1
        e = e + 1
        connectivity(:, e) = [polar_id(k, s), polar_id(k + 1, s), polar_id(k + 1, s + 1), polar_id(k, s + 1)]
        if (s == 0) call add_edge(e, 1, edge_set_axis)
        if (s == narc - 1) call add_edge(e, 3, edge_set_axis)
        if (k == nlayer - 1) call add_edge(e, 2, edge_set_outer)
      end do
    end do

  contains

    !> Angle of the core boundary path point s: 45 deg over the bottom side,
    !> 90 deg over the right side, 45 deg over the top side.
    pure real(dp) function core_angle(path)
      integer, intent(in) :: path
      if (path <= ncore_r) then
        core_angle = 0.25_dp*pi*real(path, dp)/ncore_r
      else if (path <= ncore_r + ncore_z) then
        core_angle = 0.25_dp*pi + 0.5_dp*pi*real(path - ncore_r, dp)/ncore_z
      else
        core_angle = 0.75_dp*pi + 0.25_dp*pi*real(path - ncore_r - ncore_z, dp)/ncore_r
      end if
    end function core_angle

    subroutine add_edge(element, side, set)
      integer, intent(in) :: element, side, set
      nedge = nedge + 1
      edge_element(nedge) = element
      edge_side(nedge) = side
      edge_set(nedge) = set
    end subroutine add_edge

    pure function polar_point(distance, angle, on_axis) result(point)
      real(dp), intent(in) :: distance, angle
      logical, intent(in) :: on_axis
      real(dp) :: point(2)
      point = [distance*sin(angle), radius - distance*cos(angle)]
      if (on_axis) point(1) = 0.0_dp
    end function polar_point
  end subroutine sphere_grid

  !> Structured nr x nz grid of the rectangle [r0, r1] x [z0, z1].
  !> Edge tags: INNER (r = r0, or AXIS when r0 = 0), OUTER, BOTTOM, TOP.
  subroutine rectangle_grid(r0, r1, z0, z1, nr, nz, xy, connectivity, edge_element, edge_side, edge_set)
    real(dp), intent(in) :: r0, r1, z0, z1
    integer, intent(in) :: nr, nz
    real(dp), allocatable, intent(out) :: xy(:, :)
    integer, allocatable, intent(out) :: connectivity(:, :), edge_element(:), edge_side(:), edge_set(:)
    integer :: i, j, e, nedge, inner_set
    allocate(xy(2, (nr + 1)*(nz + 1)), connectivity(4, nr*nz))
    allocate(edge_element(2*(nr + nz)), edge_side(2*(nr + nz)), edge_set(2*(nr + nz)))
    inner_set = merge(edge_set_axis, edge_set_inner, r0 == 0.0_dp)
    do j = 0, nz
      do i = 0, nr
        xy(:, id(i, j)) = [r0 + (r1 - r0)*real(i, dp)/nr, z0 + (z1 - z0)*real(j, dp)/nz]
      end do
    end do
    e = 0
    nedge = 0
    do j = 0, nz - 1
      do i = 0, nr - 1
        e = e + 1
        connectivity(:, e) = [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]
        if (j == 0) call add(e, 1, edge_set_bottom)
        if (i == nr - 1) call add(e, 2, edge_set_outer)
        if (j == nz - 1) call add(e, 3, edge_set_top)
        if (i == 0) call add(e, 4, inner_set)
      end do
    end do
  contains
    pure integer function id(ii, jj)
      integer, intent(in) :: ii, jj
      id = jj*(nr + 1) + ii + 1
    end function id
    subroutine add(element, side, set)
      integer, intent(in) :: element, side, set
      nedge = nedge + 1
      edge_element(nedge) = element
      edge_side(nedge) = side
      edge_set(nedge) = set
    end subroutine add
  end subroutine rectangle_grid

  !> Structured nr x nt grid of the ring sector r0 <= rho <= r1, 0 <= phi <= angle
  !> (degrees, from the r axis toward z), centred at the origin. For plane-strain
  !> Lame problems: INNER (rho = r0), OUTER (rho = r1), BOTTOM (phi = 0) and,
  !> for a quarter ring, AXIS (phi = 90 deg, on r = 0).
  subroutine ring_grid(r0, r1, angle, nr, nt, xy, connectivity, edge_element, edge_side, edge_set)
    real(dp), intent(in) :: r0, r1, angle
    integer, intent(in) :: nr, nt
    real(dp), allocatable, intent(out) :: xy(:, :)
    integer, allocatable, intent(out) :: connectivity(:, :), edge_element(:), edge_side(:), edge_set(:)
    real(dp) :: rho, phi
    integer :: i
    ! The rectangle (rho, phi) in [r0, r1] x [0, angle], mapped to the plane.
    call rectangle_grid(r0, r1, 0.0_dp, angle, nr, nt, xy, connectivity, edge_element, edge_side, edge_set)
    do i = 1, size(xy, 2)
      rho = xy(1, i)
      phi = xy(2, i)*pi/180.0_dp
      xy(:, i) = [rho*cos(phi), rho*sin(phi)]
      if (abs(angle - 90.0_dp) < 1.0e-9_dp .and. i > size(xy, 2) - (nr + 1)) xy(1, i) = 0.0_dp
    end do
    if (abs(angle - 90.0_dp) < 1.0e-9_dp) where (edge_set == edge_set_top) edge_set = edge_set_axis
  end subroutine ring_grid
end module visco2d_mesh_generator
