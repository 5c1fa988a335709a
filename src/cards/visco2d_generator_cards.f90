!> The fields of the MESH generator cards (SPHERE, SPHEROID, OUTLINE, RECT,
!> RING), each checked with a located error, and the grid generated once its
!> size is known to fit the limits; visco2d_mesh_cards puts it in the mesh input.
module visco2d_generator_cards
  use, intrinsic :: iso_fortran_env, only: int64
  use visco2d_kinds, only: dp
  use visco2d_error, only: error_t
  use visco2d_cards, only: card_t, card_deck_t, card_error, named_real, named_integer, named_word, &
                           positional_real, positional_word, positional_count, check_fields_used, field_column, &
                           has_field
  use visco2d_mesh_generator, only: spheroid_grid, rectangle_grid, ring_grid, sphere_default_grade, &
                                    sphere_default_core, sphere_grid_contact, sphere_grid_legacy, &
                                    spheroid_least_ratio, spheroid_largest_ratio
  use visco2d_outline_grid, only: outline_t, check_outline, make_outline, outline_grid, outline_max_points
  use visco2d_budget, only: run_size_t, mesh_run_size, sphere_mesh_counts, grid_mesh_counts, memory_limit, &
                            bytes_text, count_text, max_mesh_entities, raise_hint
  use visco2d_ranges, only: max_coordinate
  use visco2d_strings, only: integer_text, message_real, to_upper
  use visco2d_mesh, only: name_length
  implicit none
  private

  public :: read_sphere_mesh, read_rect_mesh, read_ring_mesh

contains

  !> MESH SPHERE, SPHEROID or OUTLINE (`kind`): the fields checked, the grid
  !> generated; its level and the material regions (SKINMAT=, SKIN_LAYERS=,
  !> COREMAT=; '' where the field is absent) returned for the caller to assign.
  subroutine read_sphere_mesh(deck, card, kind, xy, connectivity, edge_element, edge_side, edge_set, &
                              level, skin_material, skin_layers, core_material, error)
    type(card_deck_t), intent(in) :: deck
    type(card_t), intent(inout) :: card
    character(*), intent(in) :: kind
    real(dp), allocatable, intent(out) :: xy(:, :)
    integer, allocatable, intent(out) :: connectivity(:, :), edge_element(:), edge_side(:), edge_set(:)
    integer, intent(out) :: level, skin_layers
    character(:), allocatable, intent(out) :: skin_material, core_material
    type(error_t), allocatable, intent(inout) :: error
    real(dp) :: equatorial, polar, grade, core
    integer :: grid
    integer(int64) :: nodes, elements, least_width
    character(:), allocatable :: grid_name, usage
    real(dp), allocatable :: r(:), z(:)
    type(outline_t) :: outline
    if (kind == 'SPHEROID') then
      usage = 'MESH SPHEROID A=.. C=.. [LEVEL=L] [MAT=id] [GRID=CONTACT|LEGACY] [GRADE=b] [CORE=c] '// &
              '[SKINMAT=id [SKIN_LAYERS=n]] [COREMAT=id]'
      call named_real(deck, card, 'A', equatorial, error); if (allocated(error)) return
      call named_real(deck, card, 'C', polar, error); if (allocated(error)) return
    else if (kind == 'OUTLINE') then
      usage = 'MESH OUTLINE [LEVEL=L] [MAT=id] [GRID=CONTACT|LEGACY] [GRADE=b] [CORE=c] '// &
              '[SKINMAT=id [SKIN_LAYERS=n]] [COREMAT=id] r1 z1 r2 z2 ... rn zn'
      call read_outline_points(deck, card, r, z, error); if (allocated(error)) return
    else
      usage = 'MESH SPHERE R=.. [LEVEL=L] [MAT=id] [GRID=CONTACT|LEGACY] [GRADE=b] [CORE=c] '// &
              '[SKINMAT=id [SKIN_LAYERS=n]] [COREMAT=id]'
      call named_real(deck, card, 'R', equatorial, error); if (allocated(error)) return
      polar = equatorial
    end if
    call named_integer(deck, card, 'LEVEL', level, error, default=1); if (allocated(error)) return
    call named_word(deck, card, 'GRID', grid_name, error, default='CONTACT'); if (allocated(error)) return
    select case (grid_name)
    case ('CONTACT'); grid = sphere_grid_contact
    case ('LEGACY'); grid = sphere_grid_legacy
    case default
      call card_error(error, deck, card, 'GRID must be CONTACT or LEGACY, got "'//grid_name//'"', &
                      field_column(card, 'GRID')); return
    end select
    call named_real(deck, card, 'GRADE', grade, error, default=sphere_default_grade(grid)); if (allocated(error)) return
    call named_real(deck, card, 'CORE', core, error, default=sphere_default_core(grid)); if (allocated(error)) return
    call named_word(deck, card, 'SKINMAT', skin_material, error, default=''); if (allocated(error)) return
    call named_integer(deck, card, 'SKIN_LAYERS', skin_layers, error, default=1); if (allocated(error)) return
    call named_word(deck, card, 'COREMAT', core_material, error, default=''); if (allocated(error)) return
    call check_fields_used(deck, card, error, usage)
    if (allocated(error)) return
    call check_regions(); if (allocated(error)) return
    if (kind == 'SPHEROID') then
      call check_semi_axis(equatorial, 'A'); if (allocated(error)) return
      call check_semi_axis(polar, 'C'); if (allocated(error)) return
      if (.not. (polar/equatorial >= spheroid_least_ratio .and. polar/equatorial <= spheroid_largest_ratio)) then
        call card_error(error, deck, card, 'C/A must be in ['//message_real(spheroid_least_ratio)//', '// &
          message_real(spheroid_largest_ratio)//'] (the range on which the stretched sphere grid is validated), got C/A = '// &
          message_real(polar/equatorial), field_column(card, 'C')); return
      end if
    else if (kind == 'SPHERE') then
      call check_semi_axis(equatorial, 'R'); if (allocated(error)) return
    end if
    if (level < 1 .or. level > 7) then
      call card_error(error, deck, card, 'LEVEL must be in 1..7 (level 7 has 360,448 elements), got '//integer_text(level), &
                      field_column(card, 'LEVEL')); return
    end if
    if (grade < 0.0_dp .or. grade > 6.0_dp) then
      call card_error(error, deck, card, 'GRADE must be in [0, 6], got '//message_real(grade), field_column(card, 'GRADE'))
      return
    end if
    if (core <= 0.05_dp .or. core >= 0.95_dp) then
      call card_error(error, deck, card, 'CORE must be in (0.05, 0.95), got '//message_real(core), field_column(card, 'CORE'))
      return
    end if
    if (grid == sphere_grid_contact .and. core > 0.5_dp) then   ! at 0.6 and GRADE=0 the map folds elements
      call card_error(error, deck, card, 'CORE must be in (0.05, 0.5] on GRID=CONTACT, got '//message_real(core), &
                      field_column(card, 'CORE')); return
    end if
    call sphere_mesh_counts(level, nodes, elements, least_width)
    call check_generated_size(deck, card, kind, nodes, elements, least_width, 'LEVEL', error)
    if (allocated(error)) return
    if (kind == 'OUTLINE') then
      call make_outline(r, z, outline)
      call outline_grid(outline, level, grade, core, grid, xy, connectivity, edge_element, edge_side, edge_set)
    else
      call spheroid_grid(equatorial, polar, level, grade, core, grid, xy, connectivity, edge_element, edge_side, &
                         edge_set)
    end if
  contains
    !> SKINMAT=, SKIN_LAYERS= and COREMAT=: ids of at most 32 characters; the
    !> skin 1 to 7 of the 8 level-1 layers (at least one layer of flesh).
    subroutine check_regions()
      if (len(skin_material) > name_length) then
        call card_error(error, deck, card, 'SKINMAT id longer than 32 characters', field_column(card, 'SKINMAT'))
      else if (len(core_material) > name_length) then
        call card_error(error, deck, card, 'COREMAT id longer than 32 characters', field_column(card, 'COREMAT'))
      else if (has_field(card, 'SKIN_LAYERS') .and. len(skin_material) == 0) then
        call card_error(error, deck, card, 'SKIN_LAYERS= needs SKINMAT=id (the skin''s material)', &
                        field_column(card, 'SKIN_LAYERS'))
      else if (skin_layers < 1 .or. skin_layers > 7) then
        call card_error(error, deck, card, 'SKIN_LAYERS must be in 1..7 (of the 8 polar layers at level 1; '// &
          'level L has 8*2^(L-1)), got '//integer_text(skin_layers), field_column(card, 'SKIN_LAYERS'))
      end if
    end subroutine check_regions

    !> A radius or semi-axis: > 0 and at most max_coordinate (m).
    subroutine check_semi_axis(value, field)
      real(dp), intent(in) :: value
      character(*), intent(in) :: field
      if (value <= 0.0_dp) then
        call card_error(error, deck, card, field//' must be > 0 m, got '//message_real(value), field_column(card, field))
      else if (value > max_coordinate) then
        call card_error(error, deck, card, field//' must be <= '//message_real(max_coordinate)//' m, got '//message_real(value), &
                        field_column(card, field))
      end if
    end subroutine check_semi_axis
  end subroutine read_sphere_mesh

  !> The points r1 z1 ... rn zn of MESH OUTLINE (the positional values after
  !> OUTLINE, in m): read, and checked as an outline (`check_outline`),
  !> with an error at the point's r field (at its z field for a z problem);
  !> refused in a deck whose GEOMETRY is PLANESTRAIN (a body of revolution).
  subroutine read_outline_points(deck, card, r, z, error)
    type(card_deck_t), intent(in) :: deck
    type(card_t), intent(inout) :: card
    real(dp), allocatable, intent(out) :: r(:), z(:)
    type(error_t), allocatable, intent(inout) :: error
    integer :: values, n, i, point
    logical :: at_z
    type(error_t), allocatable :: problem
    do i = 1, deck%count
      if (deck%cards(i)%keyword /= 'GEOMETRY' .or. positional_count(deck%cards(i)) < 1) cycle
      if (to_upper(deck%cards(i)%tokens(deck%cards(i)%positions(1))%value) /= 'PLANESTRAIN') cycle
      call card_error(error, deck, card, 'MESH OUTLINE is a body of revolution: it needs GEOMETRY AXISYMMETRIC '// &
        '(the GEOMETRY card on line '//integer_text(deck%cards(i)%line)//' says PLANESTRAIN)', field_column(card, '1'))
      return
    end do
    values = positional_count(card) - 1
    if (mod(values, 2) /= 0) then
      call card_error(error, deck, card, 'the outline''s points come in pairs r z (m), got '//integer_text(values)// &
        ' values: the last point has no z', field_column(card, integer_text(values + 1))); return
    end if
    n = values/2
    if (n > outline_max_points) then
      call card_error(error, deck, card, 'the outline has '//integer_text(n)//' points, more than '// &
        integer_text(outline_max_points), field_column(card, '1')); return
    end if
    allocate(r(n), z(n))
    do i = 1, n
      call positional_real(deck, card, 2*i, 'r of point '//integer_text(i)//' (m)', r(i), error); if (allocated(error)) return
      call positional_real(deck, card, 2*i + 1, 'z of point '//integer_text(i)//' (m)', z(i), error)
      if (allocated(error)) return
      if (max(abs(r(i)), abs(z(i))) > max_coordinate) then
        call card_error(error, deck, card, 'point '//integer_text(i)//' is out of range: coordinates must be in [-'// &
          message_real(max_coordinate)//', '//message_real(max_coordinate)//'] m', field_column(card, integer_text(2*i))); return
      end if
    end do
    call check_outline(r, z, problem, point, at_z)
    if (.not. allocated(problem)) return
    if (point == 0) then
      call card_error(error, deck, card, 'the outline '//problem%message, field_column(card, '1'))
    else
      call card_error(error, deck, card, problem%message, field_column(card, integer_text(2*point + merge(1, 0, at_z))))
    end if
  end subroutine read_outline_points

  !> MESH RECT: the fields checked, the grid generated.
  subroutine read_rect_mesh(deck, card, xy, connectivity, edge_element, edge_side, edge_set, error)
    type(card_deck_t), intent(in) :: deck
    type(card_t), intent(inout) :: card
    real(dp), allocatable, intent(out) :: xy(:, :)
    integer, allocatable, intent(out) :: connectivity(:, :), edge_element(:), edge_side(:), edge_set(:)
    type(error_t), allocatable, intent(inout) :: error
    real(dp) :: r0, r1, z0, z1
    integer :: nr, nz
    integer(int64) :: nodes, elements, least_width
    call named_real(deck, card, 'R0', r0, error); if (allocated(error)) return
    call named_real(deck, card, 'R1', r1, error); if (allocated(error)) return
    call named_real(deck, card, 'Z0', z0, error); if (allocated(error)) return
    call named_real(deck, card, 'Z1', z1, error); if (allocated(error)) return
    call named_integer(deck, card, 'NR', nr, error); if (allocated(error)) return
    call named_integer(deck, card, 'NZ', nz, error); if (allocated(error)) return
    call check_fields_used(deck, card, error, 'MESH RECT R0=.. R1=.. Z0=.. Z1=.. NR=.. NZ=.. [MAT=id]')
    if (allocated(error)) return
    if (r1 <= r0 .or. z1 <= z0) then
      call card_error(error, deck, card, 'need R1 > R0 and Z1 > Z0', field_column(card, trim(merge('R1', 'Z1', r1 <= r0))))
      return
    end if
    if (max(abs(r0), abs(r1), abs(z0), abs(z1)) > max_coordinate) then
      call card_error(error, deck, card, 'R0, R1, Z0 and Z1 must be in [-'//message_real(max_coordinate)//', '// &
                      message_real(max_coordinate)//'] m'); return
    end if
    if (nr < 1) then
      call card_error(error, deck, card, 'NR must be >= 1, got '//integer_text(nr), field_column(card, 'NR')); return
    end if
    if (nz < 1) then
      call card_error(error, deck, card, 'NZ must be >= 1, got '//integer_text(nz), field_column(card, 'NZ')); return
    end if
    call grid_mesh_counts(nr, nz, nodes, elements, least_width)
    call check_generated_size(deck, card, 'RECT', nodes, elements, least_width, trim(merge('NR', 'NZ', nr >= nz)), error)
    if (allocated(error)) return
    call rectangle_grid(r0, r1, z0, z1, nr, nz, xy, connectivity, edge_element, edge_side, edge_set)
  end subroutine read_rect_mesh

  !> MESH RING: the fields checked, the grid generated (ANGLE in degrees).
  subroutine read_ring_mesh(deck, card, xy, connectivity, edge_element, edge_side, edge_set, error)
    type(card_deck_t), intent(in) :: deck
    type(card_t), intent(inout) :: card
    real(dp), allocatable, intent(out) :: xy(:, :)
    integer, allocatable, intent(out) :: connectivity(:, :), edge_element(:), edge_side(:), edge_set(:)
    type(error_t), allocatable, intent(inout) :: error
    real(dp) :: r0, r1, angle
    integer :: nr, nt
    integer(int64) :: nodes, elements, least_width
    call named_real(deck, card, 'R0', r0, error); if (allocated(error)) return
    call named_real(deck, card, 'R1', r1, error); if (allocated(error)) return
    call named_real(deck, card, 'ANGLE', angle, error, default=90.0_dp); if (allocated(error)) return
    call named_integer(deck, card, 'NR', nr, error); if (allocated(error)) return
    call named_integer(deck, card, 'NT', nt, error); if (allocated(error)) return
    call check_fields_used(deck, card, error, 'MESH RING R0=.. R1=.. NR=.. NT=.. [ANGLE=90] [MAT=id]')
    if (allocated(error)) return
    if (r0 <= 0.0_dp .or. r1 <= r0) then
      call card_error(error, deck, card, 'need 0 < R0 < R1', field_column(card, trim(merge('R0', 'R1', r0 <= 0.0_dp))))
      return
    end if
    if (angle <= 0.0_dp .or. angle > 90.0_dp) then
      call card_error(error, deck, card, 'ANGLE must be in (0, 90] degrees', field_column(card, 'ANGLE')); return
    end if
    if (r1 > max_coordinate) then
      call card_error(error, deck, card, 'R1 must be <= '//message_real(max_coordinate)//' m, got '//message_real(r1), &
                      field_column(card, 'R1')); return
    end if
    if (nr < 1) then
      call card_error(error, deck, card, 'NR must be >= 1, got '//integer_text(nr), field_column(card, 'NR')); return
    end if
    if (nt < 1) then
      call card_error(error, deck, card, 'NT must be >= 1, got '//integer_text(nt), field_column(card, 'NT')); return
    end if
    call grid_mesh_counts(nr, nt, nodes, elements, least_width)
    call check_generated_size(deck, card, 'RING', nodes, elements, least_width, trim(merge('NR', 'NT', nr >= nt)), error)
    if (allocated(error)) return
    call ring_grid(r0, r1, angle, nr, nt, xy, connectivity, edge_element, edge_side, edge_set)
  end subroutine read_ring_mesh

  !> Refuse, before generating it, a mesh larger than max_mesh_entities or
  !> on which even a STATIC run would need more memory than the limit
  !> (with the least half-bandwidth of the grid, so the refusal is sure).
  subroutine check_generated_size(deck, card, kind, nodes, elements, least_width, field, error)
    type(card_deck_t), intent(in) :: deck
    type(card_t), intent(in) :: card
    character(*), intent(in) :: kind, field
    integer(int64), intent(in) :: nodes, elements, least_width
    type(error_t), allocatable, intent(inout) :: error
    type(run_size_t) :: least
    real(dp) :: limit
    character(:), allocatable :: origin, what, solver
    logical :: raisable
    what = 'MESH '//kind//' makes '//count_text(nodes)//' nodes and '//count_text(elements)//' elements'
    if (max(nodes, elements) > max_mesh_entities) then
      call card_error(error, deck, card, what//', more than '//count_text(max_mesh_entities), &
                      field_column(card, field)); return
    end if
    least = mesh_run_size(nodes, elements, least_width, sparse=sparse_factor_declared(deck))
    call memory_limit(limit, origin, raisable)
    if (least%total_bytes <= limit) return
    solver = ''
    if (least%factor_bytes > 0.0_dp) solver = ', factored by CHOLMOD'
    call card_error(error, deck, card, what//': a run on it needs at least '//bytes_text(least%total_bytes)// &
      ' (the stiffness and its factor alone take '//bytes_text(least%band_bytes + least%factor_bytes)//': '// &
      count_text(2*nodes)//' equations, half-bandwidth at least '//count_text(least_width)//solver// &
      '), more than '//origin//raise_hint(raisable), field_column(card, field))
  end subroutine check_generated_size

  !> Whether CHOLMOD will factor the matrix (no SOLVER card, or SOLVER
  !> CHOLMOD), read ahead of the SOLVER card so that the least memory of a
  !> generated mesh counts the sparse factor before the grid is made. A
  !> SOLVER card naming no solver counts as BAND (the smaller need): its own
  !> error comes when it is read.
  logical function sparse_factor_declared(deck) result(sparse)
    type(card_deck_t), intent(in) :: deck
    type(card_t) :: card
    type(error_t), allocatable :: ignored
    character(:), allocatable :: word
    integer :: k
    sparse = .true.
    do k = 1, deck%count
      if (deck%cards(k)%keyword /= 'SOLVER') cycle
      card = deck%cards(k)
      call positional_word(deck, card, 1, 'solver', word, ignored)
      sparse = .not. allocated(ignored) .and. word == 'CHOLMOD'
      return
    end do
  end function sparse_factor_declared
end module visco2d_generator_cards
