!> The mesh of a BODY card: a second deformable body, a sphere meshed by the
!> sphere generator (the contact grid of MESH SPHERE, at the card's R and
!> LEVEL) and mirrored in z, so that its graded contact pole is on top,
!> placed on the axis under the first body (its top pole GAP below the first
!> body's lowest node) and appended to the first body's mesh: its nodes and
!> elements numbered after the first body's, marked by pad%first_node and
!> pad%first_element as a PAD's are, its upper boundary (the nodes of its
!> upper half, by increasing r) as pad%surface. The first body's boundary
!> nodes touch that surface node to segment (visco2d_contact), with the
!> pad's multi-point constraints and inelastic projection
!> (visco2d_pad_projection); the surface is curved, so each contact node
!> measures its gap from the undeformed surface under it.
module visco2d_body_mesh
  use visco2d_kinds, only: dp, geometry_axisymmetric
  use visco2d_error, only: error_t
  use visco2d_strings, only: integer_text
  use visco2d_mesh_build, only: bandwidth_numbering
  use visco2d_mesh_generator, only: sphere_grid, sphere_default_grade, sphere_default_core, sphere_grid_contact, &
                                    edge_set_outer
  use visco2d_deck_types, only: deck_t, line_error
  use visco2d_sorting, only: sorted_order
  implicit none
  private

  public :: append_body, body_surface, contact_card_line, contact_card_name

contains

  !> The second body of deck%body appended to the first body's mesh: the
  !> mirrored sphere grid, its material, numbering after the first body's,
  !> the bandwidth renumbering redone over both; pad%first_node,
  !> pad%first_element and pad%surface mark it.
  subroutine append_body(deck, error)
    type(deck_t), intent(inout) :: deck
    type(error_t), allocatable, intent(inout) :: error
    real(dp), allocatable :: xy(:, :), grown_xy(:, :)
    integer, allocatable :: connectivity(:, :), edge_element(:), edge_side(:), edge_set(:), grown(:, :)
    integer, allocatable :: outer(:)
    real(dp) :: top
    integer :: k, n, m, nodes, elements, first_id, first_element_id
    associate (body => deck%body, mesh => deck%mesh)
    if (deck%settings%geometry /= geometry_axisymmetric) then
      call line_error(error, deck, body%line, 'BODY needs GEOMETRY AXISYMMETRIC (two spheres head on, on the axis)')
      return
    end if
    body%material_index = 0
    do k = 1, size(deck%materials)
      if (deck%materials(k)%id == body%material) body%material_index = k
    end do
    if (body%material_index == 0) then
      call line_error(error, deck, body%line, 'the second body''s material '//body%material//' is not defined by a '// &
                      'MATERIAL card', 'MAT'); return
    end if
    if (deck%materials(body%material_index)%density <= 0.0_dp) then
      call line_error(error, deck, deck%materials(body%material_index)%line, 'material '//body%material// &
        ' (the second body''s, BODY card on line '//integer_text(body%line)//') has no density: ANALYSIS DYNAMIC '// &
        'needs RHO= > 0', 'RHO'); return
    end if
    call sphere_grid(body%radius, body%level, sphere_default_grade(sphere_grid_contact), &
                     sphere_default_core(sphere_grid_contact), sphere_grid_contact, xy, connectivity, edge_element, &
                     edge_side, edge_set)
    ! The outer boundary's nodes (the sphere's surface), before the mirror changes the sides' order.
    allocate(outer(0))
    do k = 1, size(edge_set)
      if (edge_set(k) /= edge_set_outer) cycle
      outer = [outer, connectivity(edge_side(k), edge_element(k)), &
               connectivity(mod(edge_side(k), 4) + 1, edge_element(k))]
    end do
    top = minval(mesh%xy(2, :)) - body%gap
    xy(2, :) = top - xy(2, :)                         ! mirrored: the contact pole (z = 0 of the grid) on top
    connectivity = connectivity([1, 4, 3, 2], :)      ! counter-clockwise again after the mirror
    n = mesh%nnode
    m = mesh%nelem
    nodes = size(xy, 2)
    elements = size(connectivity, 2)
    first_id = maxval(mesh%node_id)
    first_element_id = maxval(mesh%element_id)
    allocate(grown_xy(2, n + nodes), grown(4, m + elements))
    grown_xy(:, 1:n) = mesh%xy
    grown_xy(:, n + 1:) = xy
    grown(:, 1:m) = mesh%connectivity
    grown(:, m + 1:) = connectivity + n
    call move_alloc(grown_xy, mesh%xy)
    call move_alloc(grown, mesh%connectivity)
    mesh%node_id = [mesh%node_id, [(first_id + k, k = 1, nodes)]]
    mesh%element_id = [mesh%element_id, [(first_element_id + k, k = 1, elements)]]
    mesh%element_line = [mesh%element_line, spread(body%line, 1, elements)]
    mesh%element_material = [mesh%element_material, spread(body%material_index, 1, elements)]
    mesh%element_material_name = [mesh%element_material_name, spread(mesh%element_material_name(1), 1, elements)]
    mesh%element_material_name(m + 1:) = body%material
    mesh%nnode = n + nodes
    mesh%nelem = m + elements
    deck%pad%first_node = n + 1
    deck%pad%first_element = m + 1
    deck%pad%material_index = body%material_index
    deck%pad%material = body%material
    deck%pad%surface = body_surface(xy, outer, top - body%radius) + n
    call bandwidth_numbering(mesh)                  ! over both bodies
    end associate
  end subroutine append_body

  !> The nodes of `outer` (indices into xy, repeats allowed) on the upper
  !> half of the sphere (z at or above its centre z = `centre`), each once,
  !> by increasing r: the surface the first body touches.
  pure function body_surface(xy, outer, centre) result(surface)
    real(dp), intent(in) :: xy(:, :)
    integer, intent(in) :: outer(:)
    real(dp), intent(in) :: centre
    integer, allocatable :: surface(:)
    integer :: k
    allocate(surface(0))
    do k = 1, size(outer)
      if (xy(2, outer(k)) < centre .or. any(surface == outer(k))) cycle
      surface = [surface, outer(k)]
    end do
    surface = surface(sorted_order(xy(1, surface)))
  end function body_surface

  !> The line of the card a contact error is located at: the BODY card with
  !> a second body, else the PAD card (`surface`: an error of the pad's
  !> constraints) or the PLATE card.
  pure integer function contact_card_line(deck, surface) result(line)
    type(deck_t), intent(in) :: deck
    logical, intent(in) :: surface
    line = deck%plate%line
    if (surface) line = deck%pad%line
    if (deck%body%line > 0) line = deck%body%line
  end function contact_card_line

  !> The keyword of that card: 'BODY', 'PAD' or 'PLATE'.
  pure function contact_card_name(deck, surface) result(name)
    type(deck_t), intent(in) :: deck
    logical, intent(in) :: surface
    character(:), allocatable :: name
    name = 'PLATE'
    if (surface) name = 'PAD'
    if (deck%body%line > 0) name = 'BODY'
  end function contact_card_name
end module visco2d_body_mesh
