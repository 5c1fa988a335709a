!> Bodies of revolution from a measured outline (`MESH OUTLINE`): the
!> profile given as points (r, z) from the contact (bottom) pole to the far
!> (top) pole, both on the axis. The points are checked (`check_outline`),
!> interpolated in polar form about the centre (the axis point halfway
!> between the poles) by a cubic spline rho(phi), phi the polar angle from
!> the contact pole's direction, with d rho/d phi = 0 at both poles (a smooth
!> body crosses its axis at right angles), and meshed by the sphere grid
!> mapped radially onto the spline (`outline_grid`).
module visco2d_outline_grid
  use visco2d_kinds, only: dp, pi
  use visco2d_error, only: error_t, set_error
  use visco2d_strings, only: integer_text, message_real
  use visco2d_roots, only: increasing_root
  use visco2d_mesh_generator, only: sphere_grid, sphere_grid_contact, edge_set_outer
  implicit none
  private

  public :: outline_t, check_outline, make_outline, outline_radius, outline_grid, outline_volume
  public :: outline_pole_curvature_radius, outline_max_points

  !> Most points an outline may have (the crossing check on a refused
  !> outline compares every pair of segments).
  integer, parameter :: outline_max_points = 10000
  !> Spline samples per interval in the checks of the interpolated outline.
  integer, parameter :: samples_per_interval = 32

  !> An outline in polar form about its centre (0, centre): the spline
  !> rho(phi) through the knots (angle(i), radius(i)), angle(1) = 0 at the
  !> contact pole and angle(n) = pi at the far pole, with second derivatives
  !> `second` (d rho/d phi = 0 at both ends).
  type :: outline_t
    real(dp) :: centre = 0.0_dp                        !< z of the centre, m
    real(dp), allocatable :: angle(:), radius(:), second(:)
  end type outline_t

contains

  !> Check the points (r, z) as an outline: `error` (not allocated if they
  !> make one) says the first problem (outline_problem's text; the caller
  !> locates it at the card and the field of `point`, 0 for the outline as a
  !> whole, its z if `at_z`).
  subroutine check_outline(r, z, error, point, at_z)
    real(dp), intent(in) :: r(:), z(:)
    type(error_t), allocatable, intent(out) :: error
    integer, intent(out) :: point
    logical, intent(out) :: at_z
    character(:), allocatable :: problem
    call outline_problem(r, z, problem, point, at_z)
    if (len(problem) > 0) call set_error(error, problem)
  end subroutine check_outline

  !> The first problem of the points (r, z) as an outline, '' if none, and
  !> the index of the point it concerns (0 for the outline as a whole;
  !> `at_z` if the problem is the point's z rather than its r):
  !> fewer than 3 points, more than outline_max_points, an end off the axis,
  !> r < 0, an interior point on the axis, a point not above the contact pole
  !> (the first point must be the body's lowest), a point repeated, a crossing, a polygon not
  !> star-shaped from the centre; then, of the interpolating spline, a
  !> radius not positive, a contact pole not convex, or a dip below the pole.
  subroutine outline_problem(r, z, problem, point, at_z)
    real(dp), intent(in) :: r(:), z(:)
    character(:), allocatable, intent(out) :: problem
    integer, intent(out) :: point
    logical, intent(out) :: at_z
    type(outline_t) :: outline
    integer :: n, i, j
    problem = ''
    point = 0
    at_z = .false.
    n = size(r)
    if (n < 3) then
      problem = 'needs at least 3 points (r z pairs: the contact pole on the axis, a point off it, the far pole '// &
                'on the axis), got '//integer_text(n)
      return
    end if
    if (n > outline_max_points) then
      problem = 'has '//integer_text(n)//' points, more than '//integer_text(outline_max_points); return
    end if
    if (r(1) /= 0.0_dp) then
      point = 1
      problem = 'outline point 1 is the contact pole and must be on the axis (r = 0), got r = '//message_real(r(1)); return
    end if
    do i = 2, n - 1
      point = i
      if (r(i) < 0.0_dp) then
        problem = 'outline point '//integer_text(i)//': r must be >= 0, got '//message_real(r(i)); return
      end if
      if (r(i) == 0.0_dp) then
        problem = 'outline point '//integer_text(i)//' is on the axis between the poles (only the first and the last point may '// &
                  'have r = 0: the body would be pinched)'; return
      end if
    end do
    point = n
    if (r(n) /= 0.0_dp) then
      problem = 'outline point '//integer_text(n)//' (the last) is the far pole and must be on the axis (r = 0), got r = '// &
                message_real(r(n)); return
    end if
    do i = 2, n
      point = i
      if (z(i) <= z(1)) then
        at_z = .true.
        problem = 'outline point '//integer_text(i)//' (z = '//message_real(z(i)) &
          //') is not above the contact pole (point 1, z = '// &
                  message_real(z(1))//'): the first point must be the lowest of the body, the pole that touches the plate'
        return
      end if
    end do
    do i = 2, n
      point = i
      if (r(i) == r(i - 1) .and. z(i) == z(i - 1)) then
        problem = 'outline point '//integer_text(i)//' repeats point '//integer_text(i - 1); return
      end if
    end do
    outline%centre = 0.5_dp*(z(1) + z(n))
    do i = 1, n - 1
      if (polar_angle(r(i + 1), z(i + 1), outline%centre) > polar_angle(r(i), z(i), outline%centre)) cycle
      do j = 1, n - 1                             ! name a crossing if there is one
        call first_crossing(j, point)
        if (point > 0) then
          problem = 'the outline crosses itself: the segment from point '//integer_text(j)//' to '//integer_text(j + 1)// &
                    ' crosses the segment from point '//integer_text(point)//' to '//integer_text(point + 1)
          point = j + 1
          return
        end if
      end do
      point = i + 1
      problem = 'the outline is not star-shaped from its centre (r = 0, z = '//message_real(outline%centre)// &
        ', halfway between the poles): point '//integer_text(i + 1)//' is not further round from the contact pole than '// &
        'point '//integer_text(i)//' (polar angles '//message_real(polar_angle(r(i), z(i), outline%centre)*180.0_dp/pi)//' and '// &
        message_real(polar_angle(r(i + 1), z(i + 1), outline%centre)*180.0_dp/pi)//' deg): every ray from the centre '// &
        'must meet the outline once'
      return
    end do
    call make_outline(r, z, outline)
    call spline_problem(outline, z(1), problem, point, at_z)
  contains
    !> The first segment k > j + 1 (not adjacent to segment j) that crosses
    !> or touches segment j, 0 if none.
    subroutine first_crossing(j, found)
      integer, intent(in) :: j
      integer, intent(out) :: found
      integer :: k
      found = 0
      do k = j + 2, n - 1
        if (segments_meet([r(j), z(j)], [r(j + 1), z(j + 1)], [r(k), z(k)], [r(k + 1), z(k + 1)])) then
          found = k
          return
        end if
      end do
    end subroutine first_crossing
  end subroutine outline_problem

  !> Problems of the interpolating spline of checked points: rho(phi) <= 0
  !> or beyond twice the points' largest rho (or not a number: points far
  !> closer in angle than their neighbours make the spline swing), a contact pole that is not convex (its curvature (rho - rho'')/rho^2 at
  !> phi = 0, rho' = 0 there, not positive), or the spline below the contact
  !> pole (z < `lowest`) off the pole. Sampled samples_per_interval times
  !> per interval.
  subroutine spline_problem(outline, lowest, problem, point, at_z)
    type(outline_t), intent(in) :: outline
    real(dp), intent(in) :: lowest
    character(:), allocatable, intent(inout) :: problem
    integer, intent(inout) :: point
    logical, intent(inout) :: at_z
    integer :: i, k
    real(dp) :: phi, rho, largest
    largest = maxval(outline%radius)
    if (.not. (outline%radius(1) - outline%second(1) > 0.0_dp)) then
      point = 2
      problem = 'the outline is not convex at the contact pole: its interpolating spline''s curvature there is '// &
        message_real((outline%radius(1) - outline%second(1))/outline%radius(1)**2)//' 1/m (the pole must touch the '// &
        'plate like a sphere: the points next to it must rise from it)'
      return
    end if
    do i = 1, size(outline%angle) - 1
      do k = 1, samples_per_interval
        phi = outline%angle(i) + (outline%angle(i + 1) - outline%angle(i))*real(k, dp)/samples_per_interval
        rho = outline_radius(outline, phi)
        point = i + 1
        if (rho <= 0.0_dp) then
          problem = 'the interpolated outline reaches the centre between points '//integer_text(i)//' and '//integer_text(i + 1)// &
                    ' (the points turn too sharply there: give more points)'
          return
        end if
        if (.not. (rho <= 2.0_dp*largest)) then
          problem = 'the interpolated outline swings out to '//message_real(rho)//' m from the centre between points '// &
            integer_text(i)//' and '//integer_text(i + 1)//', beyond twice the points'' largest distance ' &
              //message_real(largest)// &
            ' m (points much closer together than their neighbours, or turning too sharply: smooth them)'
          return
        end if
        if (outline%centre - rho*cos(phi) <= lowest) then
          at_z = .true.
          problem = 'the interpolated outline dips below the contact pole (z = '//message_real(lowest)//') between points '// &
            integer_text(i)//' and '//integer_text(i + 1)//' (z = '//message_real(outline%centre - rho*cos(phi)) &
              //'): the pole must be '// &
            'the lowest point of the body (give more points near the pole)'
          return
        end if
      end do
    end do
    point = 0
  end subroutine spline_problem

  !> Polar angle of (r, z) about the centre (0, centre), from the direction
  !> of the contact pole (-z): 0 at the contact pole, pi at the far pole.
  pure real(dp) function polar_angle(r, z, centre)
    real(dp), intent(in) :: r, z, centre
    polar_angle = atan2(r, centre - z)
  end function polar_angle

  !> Do the closed segments [a, b] and [c, d] meet (cross or touch)?
  pure logical function segments_meet(a, b, c, d)
    real(dp), intent(in) :: a(2), b(2), c(2), d(2)
    real(dp) :: o1, o2, o3, o4
    o1 = orientation(a, b, c)
    o2 = orientation(a, b, d)
    o3 = orientation(c, d, a)
    o4 = orientation(c, d, b)
    if (o1 == 0.0_dp .and. o2 == 0.0_dp) then      ! collinear: do the projections overlap?
      segments_meet = overlap(a(1), b(1), c(1), d(1)) .and. overlap(a(2), b(2), c(2), d(2))
    else
      segments_meet = o1*o2 <= 0.0_dp .and. o3*o4 <= 0.0_dp
    end if
  contains
    pure real(dp) function orientation(p, q, s)
      real(dp), intent(in) :: p(2), q(2), s(2)
      orientation = (q(1) - p(1))*(s(2) - p(2)) - (q(2) - p(2))*(s(1) - p(1))
    end function orientation
    pure logical function overlap(p1, p2, q1, q2)
      real(dp), intent(in) :: p1, p2, q1, q2
      overlap = max(min(p1, p2), min(q1, q2)) <= min(max(p1, p2), max(q1, q2))
    end function overlap
  end function segments_meet

  !> The outline of checked points (r, z) (`outline_problem` found none): the
  !> centre halfway between the poles, the knots in polar form, and the
  !> clamped cubic spline's second derivatives (d rho/d phi = 0 at phi = 0
  !> and pi), by the tridiagonal (Thomas) solve.
  pure subroutine make_outline(r, z, outline)
    real(dp), intent(in) :: r(:), z(:)
    type(outline_t), intent(out) :: outline
    real(dp), allocatable :: h(:), diagonal(:), right(:)
    real(dp) :: factor
    integer :: n, i
    n = size(r)
    outline%centre = 0.5_dp*(z(1) + z(n))
    allocate(outline%angle(n), outline%radius(n), outline%second(n), h(n - 1), diagonal(n), right(n))
    do i = 1, n
      outline%angle(i) = polar_angle(r(i), z(i), outline%centre)
      outline%radius(i) = hypot(r(i), z(i) - outline%centre)
    end do
    outline%angle(1) = 0.0_dp
    outline%angle(n) = pi
    h = outline%angle(2:n) - outline%angle(1:n - 1)
    associate (y => outline%radius, m => outline%second)
      ! Row i: h(i-1) m(i-1) + 2 (h(i-1) + h(i)) m(i) + h(i) m(i+1) = 6 (slope(i) - slope(i-1)),
      ! with the end slopes 0 (rows 1 and n).
      diagonal(1) = 2.0_dp*h(1)
      right(1) = 6.0_dp*(y(2) - y(1))/h(1)
      do i = 2, n - 1
        diagonal(i) = 2.0_dp*(h(i - 1) + h(i))
        right(i) = 6.0_dp*((y(i + 1) - y(i))/h(i) - (y(i) - y(i - 1))/h(i - 1))
      end do
      diagonal(n) = 2.0_dp*h(n - 1)
      right(n) = -6.0_dp*(y(n) - y(n - 1))/h(n - 1)
      do i = 2, n                                  ! elimination (sub- and super-diagonal h(i-1))
        factor = h(i - 1)/diagonal(i - 1)
        diagonal(i) = diagonal(i) - factor*h(i - 1)
        right(i) = right(i) - factor*right(i - 1)
      end do
      m(n) = right(n)/diagonal(n)
      do i = n - 1, 1, -1
        m(i) = (right(i) - h(i)*m(i + 1))/diagonal(i)
      end do
    end associate
  end subroutine make_outline

  !> The outline's distance rho(phi) from its centre at the polar angle phi
  !> (0 at the contact pole, pi at the far pole): the cubic spline.
  pure real(dp) function outline_radius(outline, phi) result(rho)
    type(outline_t), intent(in) :: outline
    real(dp), intent(in) :: phi
    integer :: low, high, middle
    real(dp) :: h, a, b
    low = 1
    high = size(outline%angle)
    do while (high - low > 1)                      ! angle(low) <= phi <= angle(high)
      middle = (low + high)/2
      if (phi < outline%angle(middle)) then
        high = middle
      else
        low = middle
      end if
    end do
    h = outline%angle(high) - outline%angle(low)
    a = (outline%angle(high) - phi)/h
    b = 1.0_dp - a
    rho = a*outline%radius(low) + b*outline%radius(high) + &
          ((a**3 - a)*outline%second(low) + (b**3 - b)*outline%second(high))*h**2/6.0_dp
  end function outline_radius

  !> Radius of curvature of the outline at the contact pole, m:
  !> rho^2/(rho - rho'') at phi = 0 (rho' = 0 there).
  pure real(dp) function outline_pole_curvature_radius(outline) result(radius)
    type(outline_t), intent(in) :: outline
    radius = outline%radius(1)**2/(outline%radius(1) - outline%second(1))
  end function outline_pole_curvature_radius

  !> Volume of revolution of the interpolated outline, m^3:
  !> 2 pi/3 times the integral of rho^3 sin(phi) over [0, pi] (5-point
  !> Gauss-Legendre on 8 equal parts of every interval).
  pure real(dp) function outline_volume(outline) result(volume)
    type(outline_t), intent(in) :: outline
    real(dp), parameter :: nodes(5) = [-0.906179845938664_dp, -0.538469310105683_dp, 0.0_dp, &
                                       0.538469310105683_dp, 0.906179845938664_dp]
    real(dp), parameter :: weights(5) = [0.236926885056189_dp, 0.478628670499366_dp, 0.568888888888889_dp, &
                                         0.478628670499366_dp, 0.236926885056189_dp]
    integer, parameter :: parts = 8
    integer :: i, p, g
    real(dp) :: low, width, phi
    volume = 0.0_dp
    do i = 1, size(outline%angle) - 1
      width = (outline%angle(i + 1) - outline%angle(i))/parts
      do p = 1, parts
        low = outline%angle(i) + (p - 1)*width
        do g = 1, 5
          phi = low + 0.5_dp*width*(1.0_dp + nodes(g))
          volume = volume + 0.5_dp*width*weights(g)*outline_radius(outline, phi)**3*sin(phi)
        end do
      end do
    end do
    volume = 2.0_dp*pi/3.0_dp*volume
  end function outline_volume

  !> The sphere grid (`sphere_grid`: same level, grid, grade and core, the
  !> same topology, edge sets, element order and so the same layers for
  !> SKINMAT=/COREMAT=) mapped radially onto the outline: the node at polar
  !> angle phi and distance s R from the sphere's centre goes to s rho(phi)
  !> from the outline's centre, along the same direction. The contact pole
  !> stays the first node ring's pole, the grading toward it is the
  !> sphere's in angle. On the contact grid the sphere's surface nodes lie
  !> s = 1 + c w beyond the sphere (its `restore_volume`); here they lie
  !> 1 + lambda c w beyond the spline, lambda (1 for a sphere) found by
  !> bisection so that the polygon's volume of revolution is the spline's
  !> (`outline_volume`). The legacy grid's nodes stay on the spline.
  subroutine outline_grid(outline, level, grade, core, grid, xy, connectivity, edge_element, edge_side, edge_set)
    type(outline_t), intent(in) :: outline
    real(dp), intent(in) :: grade, core
    integer, intent(in) :: level, grid
    real(dp), allocatable, intent(out) :: xy(:, :)
    integer, allocatable, intent(out) :: connectivity(:, :), edge_element(:), edge_side(:), edge_set(:)
    real(dp), allocatable :: direction(:, :), excess(:), distance(:)
    integer, allocatable :: surface(:)
    real(dp) :: s, phi, rho
    integer :: i
    call sphere_grid(1.0_dp, level, grade, core, grid, xy, connectivity, edge_element, edge_side, edge_set)
    surface = surface_nodes(connectivity, edge_element, edge_side, edge_set)
    allocate(direction(2, size(surface)), excess(size(surface)), distance(size(surface)))
    do i = 1, size(surface)
      excess(i) = norm2(xy(:, surface(i)) - [0.0_dp, 1.0_dp]) - 1.0_dp
    end do
    do i = 1, size(xy, 2)
      s = norm2(xy(:, i) - [0.0_dp, 1.0_dp])
      phi = polar_angle(xy(1, i), xy(2, i), 1.0_dp)
      rho = outline_radius(outline, phi)
      xy(:, i) = [merge(0.0_dp, s*rho*sin(phi), xy(1, i) == 0.0_dp), outline%centre - s*rho*cos(phi)]
    end do
    do i = 1, size(surface)
      direction(:, i) = xy(:, surface(i)) - [0.0_dp, outline%centre]
      distance(i) = norm2(direction(:, i))
      direction(:, i) = direction(:, i)/distance(i)
    end do
    if (grid == sphere_grid_contact) call restore_outline_volume()
  contains
    !> Surface node i at (1 + lambda excess_i) rho_i / (1 + excess_i) of its
    !> mapped distance, lambda found by bisection (the volume increases with it).
    subroutine restore_outline_volume()
      call place(increasing_root(surface_volume, outline_volume(outline)))
    end subroutine restore_outline_volume

    subroutine place(lambda)
      real(dp), intent(in) :: lambda
      integer :: k
      do k = 1, size(surface)
        xy(:, surface(k)) = [0.0_dp, outline%centre] + &
          distance(k)*(1.0_dp + lambda*excess(k))/(1.0_dp + excess(k))*direction(:, k)
      end do
      xy(1, surface(1)) = 0.0_dp
      xy(1, surface(size(surface))) = 0.0_dp
    end subroutine place

    !> Volume of revolution of the section bounded by the axis and the
    !> surface polygon at lambda: the frusta pi/3 (r_a^2 + r_a r_b + r_b^2)(z_b - z_a).
    real(dp) function surface_volume(lambda)
      real(dp), intent(in) :: lambda
      real(dp) :: a(2), b(2)
      integer :: k
      call place(lambda)
      surface_volume = 0.0_dp
      do k = 2, size(surface)
        a = xy(:, surface(k - 1))
        b = xy(:, surface(k))
        surface_volume = surface_volume + pi/3.0_dp*(a(1)**2 + a(1)*b(1) + b(1)**2)*(b(2) - a(2))
      end do
    end function surface_volume
  end subroutine outline_grid

  !> The sphere grid's surface nodes in order from the contact pole: the
  !> OUTER edges, each side 2 of its element (nodes 2 to 3), in the order
  !> the grid makes them.
  pure function surface_nodes(connectivity, edge_element, edge_side, edge_set) result(nodes)
    integer, intent(in) :: connectivity(:, :), edge_element(:), edge_side(:), edge_set(:)
    integer, allocatable :: nodes(:)
    integer :: k
    allocate(nodes(0))
    do k = 1, size(edge_element)
      if (edge_set(k) /= edge_set_outer) cycle
      if (size(nodes) == 0) nodes = [connectivity(edge_side(k), edge_element(k))]
      nodes = [nodes, connectivity(mod(edge_side(k), 4) + 1, edge_element(k))]
    end do
  end function surface_nodes
end module visco2d_outline_grid
