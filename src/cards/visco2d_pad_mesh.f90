!> The mesh of a PAD card: a layer of one material between the body and the
!> rigid plate, meshed as an r-z grid under the body and appended to the
!> body's mesh (its nodes and elements numbered after the body's, so that
!> they are the last ones in storage order; pad%first_node and
!> pad%first_element mark them). Out to 0.4 of the body's radius (beyond
!> any contact radius of a fruit drop) the pad's surface nodes lie under
!> the body's boundary nodes, at the same r: the two sides of the contact
!> are discretized alike and the node-to-segment forces land on pad nodes
!> (on a finer pad surface each body node would load it as a point and
!> indent it locally: 5 % more approach in the Hertz check of test_pad).
!> Beyond, the columns grow by 1.2 out to the width; the rows grow by 1.2
!> downward from the body's element size at its pole. With SIZE= the
!> surface is uniform with that size out to 0.4 of the radius instead. The
!> pad's bottom is held on the rigid plate (in z, and in r with
!> BOTTOM=BONDED) by a support added to the deck's FIX list; its axis is
!> held in r like every axis node. The contact of the body with the pad's
!> top surface is visco2d_contact's (node to segment).
module visco2d_pad_mesh
  use visco2d_kinds, only: dp, geometry_axisymmetric
  use visco2d_error, only: error_t
  use visco2d_strings, only: integer_text, message_real
  use visco2d_mesh_build, only: bandwidth_numbering
  use visco2d_mesh, only: boundary_sides
  use visco2d_deck_types, only: deck_t, fix_t, line_error, add_warning, analysis_dynamic
  use visco2d_sorting, only: sorted_order
  implicit none
  private

  public :: append_pad, pad_grid_lines, is_pad_node, is_pad_element, body_nodes, body_elements

  !> Growth of the element size away from the impact point, in r and in depth.
  real(dp), parameter :: growth = 1.2_dp
  !> The uniform part of the grid: this fraction of the body's largest r.
  real(dp), parameter :: uniform_fraction = 0.4_dp
  !> Default width: this multiple of the body's largest r.
  real(dp), parameter :: default_width = 1.5_dp
  !> Largest number of grid lines in r or z (a size far too small for the pad).
  integer, parameter :: max_lines = 2000

contains

  !> True for a node of the pad (node index in storage order).
  pure logical function is_pad_node(deck, node)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: node
    is_pad_node = deck%pad%first_node > 0 .and. node >= deck%pad%first_node
  end function is_pad_node

  !> True for an element of the pad.
  pure logical function is_pad_element(deck, element)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: element
    is_pad_element = deck%pad%first_element > 0 .and. element >= deck%pad%first_element
  end function is_pad_element

  !> The body's nodes are 1..body_nodes (all of them without a pad).
  pure integer function body_nodes(deck)
    type(deck_t), intent(in) :: deck
    body_nodes = deck%mesh%nnode
    if (deck%pad%first_node > 0) body_nodes = deck%pad%first_node - 1
  end function body_nodes

  !> The body's elements are 1..body_elements (all of them without a pad).
  pure integer function body_elements(deck)
    type(deck_t), intent(in) :: deck
    body_elements = deck%mesh%nelem
    if (deck%pad%first_element > 0) body_elements = deck%pad%first_element - 1
  end function body_elements

  !> Grid lines from 0 to `length`: steps of `size` up to `uniform`, then
  !> growing by `growth`; the last step is stretched (or merged with the one
  !> before, if it would be under half of it) to end exactly at `length`.
  !> At least `least` steps; none (an empty result) if more than
  !> max_lines would be needed.
  pure function pad_grid_lines(length, size, uniform, least) result(lines)
    real(dp), intent(in) :: length, size, uniform
    integer, intent(in) :: least
    real(dp), allocatable :: lines(:)
    real(dp) :: buffer(0:max_lines), step
    integer :: n, k
    if (length <= least*size) then
      lines = [(length*k/real(least, dp), k = 0, least)]
      return
    end if
    buffer(0) = 0.0_dp
    step = size
    n = 0
    do while (buffer(n) + step < length)
      if (n == max_lines - 1) then
        allocate(lines(0))
        return
      end if
      n = n + 1
      buffer(n) = buffer(n - 1) + step
      if (buffer(n) >= uniform) step = step*growth
    end do
    if (length - buffer(n) < 0.5_dp*(buffer(n) - buffer(max(n - 1, 0))) .and. n > least - 1 .and. n > 1) n = n - 1
    n = n + 1
    buffer(n) = length
    lines = buffer(0:n)
  end function pad_grid_lines

  !> The pad of deck%pad appended to the body's mesh: its grid, material,
  !> numbering after the body's, the bandwidth renumbering redone over both,
  !> the bottom support; the surface and bottom node lists.
  subroutine append_pad(deck, error)
    type(deck_t), intent(inout) :: deck
    type(error_t), allocatable, intent(inout) :: error
    real(dp), allocatable :: r_lines(:), z_lines(:)
    real(dp) :: reach, spacing, width, top
    integer :: k, nr, nz, i, j, base_node, base_element, node_count, element_count
    associate (pad => deck%pad, mesh => deck%mesh)
    if (deck%settings%geometry /= geometry_axisymmetric) then
      call line_error(error, deck, pad%line, 'PAD needs GEOMETRY AXISYMMETRIC (a pad under a plane-strain body '// &
                      'is not built)'); return
    end if
    call pad_material(deck, error); if (allocated(error)) return
    reach = maxval(abs(mesh%xy(1, :)))
    width = pad%width
    if (width == 0.0_dp) width = default_width*reach
    spacing = pad%size
    if (spacing == 0.0_dp) spacing = pole_edge(deck)
    if (pad%size > 0.0_dp .and. pad%size < 0.5_dp*pole_edge(deck)) call add_warning(deck, pad%line, 'PAD', &
      'SIZE = '//message_real(pad%size)//' m is under half the body''s element size at its pole (' &
        //message_real(pole_edge(deck))// &
      ' m): each body node then loads the finer pad surface like a point and indents it locally (large local '// &
      'strains, too much compression); leave SIZE out to put the pad''s nodes under the body''s')
    if (width < reach) call add_warning(deck, pad%line, 'PAD', 'WIDTH = '//message_real(width)//' m is less than the '// &
      'body''s radius '//message_real(reach)//' m: body nodes beyond the pad''s edge find nothing to touch')
    if (spacing > 0.5_dp*min(width, pad%thickness*4.0_dp)) then
      call line_error(error, deck, pad%line, 'SIZE = '//message_real(spacing)//' m is too coarse for a pad '// &
        message_real(pad%thickness)//' m thick and '//message_real(width)//' m wide (at most half the width and twice the '// &
        'thickness)', merge('SIZE     ', 'THICKNESS', pad%size > 0.0_dp)); return
    end if
    if (pad%size > 0.0_dp) then
      r_lines = pad_grid_lines(width, spacing, uniform_fraction*reach, 2)
    else
      r_lines = matched_lines(deck, width, uniform_fraction*reach)
    end if
    z_lines = depth_lines(pad%thickness, pad%cover, spacing)
    if (size(r_lines) == 0 .or. size(z_lines) == 0) then
      call line_error(error, deck, pad%line, 'SIZE = '//message_real(spacing)//' m is too fine: the pad would need more '// &
                      'than '//integer_text(max_lines)//' grid lines across its width or thickness', 'SIZE'); return
    end if
    nr = size(r_lines) - 1
    nz = size(z_lines) - 1
    top = deck%plate%z
    base_node = mesh%nnode
    base_element = mesh%nelem
    node_count = (nr + 1)*(nz + 1)
    element_count = nr*nz
    call grow_mesh(deck, node_count, element_count)
    do j = 0, nz                                          ! rows from the top surface down
      do i = 0, nr
        k = base_node + j*(nr + 1) + i + 1
        mesh%xy(:, k) = [r_lines(i + 1), top - z_lines(j + 1)]
        mesh%node_id(k) = mesh%node_id(base_node) + k - base_node
      end do
    end do
    do j = 1, nz
      do i = 1, nr                                        ! counter-clockwise in (r, z): row j lies below row j-1
        k = base_element + (j - 1)*nr + i
        mesh%connectivity(:, k) = base_node + [j*(nr + 1) + i, j*(nr + 1) + i + 1, (j - 1)*(nr + 1) + i + 1, &
                                               (j - 1)*(nr + 1) + i]
        mesh%element_id(k) = mesh%element_id(base_element) + k - base_element
        mesh%element_line(k) = pad%line
        if (z_lines(j + 1) <= pad%cover*(1.0_dp + 1.0e-9_dp)) then    ! row j lies within the cover
          mesh%element_material(k) = pad%cover_index
          mesh%element_material_name(k) = pad%cover_material
        else
          mesh%element_material(k) = pad%material_index
          mesh%element_material_name(k) = pad%material
        end if
      end do
    end do
    pad%first_node = base_node + 1
    pad%first_element = base_element + 1
    pad%surface = [(base_node + i, i = 1, nr + 1)]
    pad%bottom = [(base_node + nz*(nr + 1) + i, i = 1, nr + 1)]
    call bandwidth_numbering(mesh)                      ! over both bodies
    call add_bottom_support(deck)
    end associate
  end subroutine append_pad

  !> The pad's bottom held on the rigid plate: a support appended to the
  !> deck's FIX list (z; r too with BOTTOM=BONDED), located at the PAD card.
  subroutine add_bottom_support(deck)
    type(deck_t), intent(inout) :: deck
    type(fix_t), allocatable :: fixes(:)
    integer :: n
    n = size(deck%loads%fixes)
    allocate(fixes(n + 1))
    fixes(1:n) = deck%loads%fixes
    fixes(n + 1)%nodes = deck%pad%bottom
    fixes(n + 1)%fix_r = deck%pad%bonded
    fixes(n + 1)%fix_z = .true.
    fixes(n + 1)%line = deck%pad%line
    call move_alloc(fixes, deck%loads%fixes)
  end subroutine add_bottom_support

  !> Grid lines in r: the r of the body's boundary nodes below its centre
  !> out to `matched`, then steps growing by `growth` from the last one out
  !> to `width` (the last stretched or merged as in pad_grid_lines).
  function matched_lines(deck, width, matched) result(lines)
    type(deck_t), intent(in) :: deck
    real(dp), intent(in) :: width, matched
    real(dp), allocatable :: lines(:), tail(:)
    real(dp), allocatable :: r(:)
    integer :: n
    r = boundary_radii(deck, min(matched, width))
    n = size(r)
    if (n < 2) then
      lines = pad_grid_lines(width, width/10.0_dp, 0.0_dp, 2)
      return
    end if
    if (width - r(n) <= 0.5_dp*(r(n) - r(n - 1))) then     ! the pad ends within the matched part
      r(n) = width
      lines = r
      return
    end if
    tail = pad_grid_lines(width - r(n), (r(n) - r(n - 1))*growth, 0.0_dp, 1)
    if (size(tail) == 0) then
      allocate(lines(0))
      return
    end if
    lines = [r, r(n) + tail(2:)]
  end function matched_lines

  !> The distinct |r| (ascending, from 0) of the body's boundary nodes that
  !> lie below its mid-height, up to `limit`.
  function boundary_radii(deck, limit) result(r)
    type(deck_t), intent(in) :: deck
    real(dp), intent(in) :: limit
    real(dp), allocatable :: r(:)
    integer, allocatable :: sides(:, :)
    logical, allocatable :: boundary(:)
    real(dp) :: middle, tolerance
    integer :: i, node
    associate (mesh => deck%mesh)
    sides = boundary_sides(mesh, mesh%nelem)
    allocate(boundary(mesh%nnode))
    boundary = .false.
    do i = 1, size(sides, 2)
      boundary(sides(:, i)) = .true.
    end do
    middle = 0.5_dp*(minval(mesh%xy(2, :)) + maxval(mesh%xy(2, :)))
    tolerance = 1.0e-9_dp*mesh%size
    allocate(r(0))
    do node = 1, mesh%nnode
      if (.not. boundary(node) .or. mesh%xy(2, node) >= middle .or. abs(mesh%xy(1, node)) > limit) cycle
      if (any(abs(r - abs(mesh%xy(1, node))) <= tolerance)) cycle
      r = [r, abs(mesh%xy(1, node))]
    end do
    end associate
    call sort_reals(r)
    if (size(r) == 0) then
      r = [0.0_dp]
    else if (r(1) > 0.0_dp) then
      r = [0.0_dp, r]                                  ! the axis
    end if
  end function boundary_radii

  !> Sort in ascending order.
  pure subroutine sort_reals(x)
    real(dp), intent(inout) :: x(:)
    x = x(sorted_order(x))
  end subroutine sort_reals

  !> Depths of the pad's rows from its top: without a cover, steps of
  !> `spacing` growing by `growth` (pad_grid_lines); with one, at least 2
  !> equal rows of at most `spacing` through the cover, then rows growing
  !> from the cover's row height down to `thickness`. Empty if too many.
  function depth_lines(thickness, cover, spacing) result(lines)
    real(dp), intent(in) :: thickness, cover, spacing
    real(dp), allocatable :: lines(:), below(:)
    integer :: n, k
    if (cover <= 0.0_dp) then
      lines = pad_grid_lines(thickness, spacing, 0.0_dp, 2)
      return
    end if
    n = max(2, ceiling(cover/spacing - 1.0e-9_dp))
    if (n > max_lines/2) then
      allocate(lines(0))
      return
    end if
    below = pad_grid_lines(thickness - cover, min(spacing, cover/n)*growth, 0.0_dp, 1)
    if (size(below) == 0) then
      allocate(lines(0))
      return
    end if
    lines = [(cover*k/real(n, dp), k = 0, n), cover + below(2:)]
  end function depth_lines

  !> The pad's material by its MAT= id (a located error if there is none, or
  !> if it has no density: the pad moves).
  subroutine pad_material(deck, error)
    type(deck_t), intent(inout) :: deck
    type(error_t), allocatable, intent(inout) :: error
    integer :: k
    associate (pad => deck%pad)
    pad%material_index = 0
    do k = 1, size(deck%materials)
      if (deck%materials(k)%id == pad%material) pad%material_index = k
    end do
    if (pad%material_index == 0) then
      call line_error(error, deck, pad%line, 'the pad''s material '//pad%material//' is not defined by a MATERIAL '// &
                      'card', 'MAT'); return
    end if
    pad%cover_index = 0
    do k = 1, size(deck%materials)
      if (deck%materials(k)%id == pad%cover_material) pad%cover_index = k
    end do
    if (pad%cover > 0.0_dp .and. pad%cover_index == 0) then
      call line_error(error, deck, pad%line, 'the cover''s material '//pad%cover_material//' is not defined by a '// &
                      'MATERIAL card', 'COVERMAT'); return
    end if
    if (pad%cover > 0.0_dp) then
      if (deck%materials(pad%cover_index)%density <= 0.0_dp .and. &
          (deck%analysis == analysis_dynamic .or. deck%gravity_line > 0)) then
        call line_error(error, deck, deck%materials(pad%cover_index)%line, 'material '//pad%cover_material// &
          ' (the pad''s cover, PAD card on line '//integer_text(pad%line)//') has no density: RHO= > 0 is needed', 'RHO')
        return
      end if
    end if
    if (deck%materials(pad%material_index)%density <= 0.0_dp .and. &
        (deck%analysis == analysis_dynamic .or. deck%gravity_line > 0)) then
      call line_error(error, deck, deck%materials(pad%material_index)%line, 'material '//pad%material// &
        ' (the pad''s, PAD card on line '//integer_text(pad%line)//') has no density: '// &
        trim(merge('ANALYSIS DYNAMIC', 'GRAVITY         ', deck%analysis == analysis_dynamic))//' needs RHO= > 0', 'RHO')
    end if
    end associate
  end subroutine pad_material

  !> The body's element size at its contact pole: the shortest distance from
  !> the lowest node (nearest the axis among equals) to a node of an element
  !> it belongs to.
  real(dp) function pole_edge(deck) result(edge)
    type(deck_t), intent(in) :: deck
    integer :: pole, e, k, node
    associate (mesh => deck%mesh)
    pole = 1
    do node = 2, mesh%nnode
      if (mesh%xy(2, node) < mesh%xy(2, pole) .or. &
          (mesh%xy(2, node) == mesh%xy(2, pole) .and. abs(mesh%xy(1, node)) < abs(mesh%xy(1, pole)))) pole = node
    end do
    edge = huge(1.0_dp)
    do e = 1, mesh%nelem
      if (.not. any(mesh%connectivity(:, e) == pole)) cycle
      do k = 1, 4
        node = mesh%connectivity(k, e)
        if (node /= pole) edge = min(edge, norm2(mesh%xy(:, node) - mesh%xy(:, pole)))
      end do
    end do
    end associate
  end function pole_edge

  !> Room for `nodes` more nodes and `elements` more elements in the mesh.
  subroutine grow_mesh(deck, nodes, elements)
    type(deck_t), intent(inout) :: deck
    integer, intent(in) :: nodes, elements
    real(dp), allocatable :: xy(:, :)
    integer, allocatable :: connectivity(:, :)
    integer :: n, m
    associate (mesh => deck%mesh)
    n = mesh%nnode
    m = mesh%nelem
    allocate(xy(2, n + nodes), connectivity(4, m + elements))
    xy(:, 1:n) = mesh%xy
    connectivity(:, 1:m) = mesh%connectivity
    call move_alloc(xy, mesh%xy)
    call move_alloc(connectivity, mesh%connectivity)
    mesh%node_id = [mesh%node_id, spread(0, 1, nodes)]
    mesh%element_id = [mesh%element_id, spread(0, 1, elements)]
    mesh%element_line = [mesh%element_line, spread(0, 1, elements)]
    mesh%element_material = [mesh%element_material, spread(0, 1, elements)]
    mesh%element_material_name = [mesh%element_material_name, spread(mesh%element_material_name(1), 1, elements)]
    mesh%nnode = n + nodes
    mesh%nelem = m + elements
    end associate
  end subroutine grow_mesh
end module visco2d_pad_mesh
