!> Mesh guards and size before work (issue 13):
!>  - node and element numbers, GEN/INC/NINC: checked in 64-bit arithmetic and
!>    refused with the field's column before anything is allocated;
!>  - elements that cover part of the body twice (same nodes, three to a side,
!>    both on one side of a side, overlapping areas), cracks (two nodes at one
!>    point) and hanging nodes: refused, naming both elements and their lines;
!>  - degenerate elements, coordinates out of range, a mesh too small to be in metres;
!>  - the run's size: a mesh too big for the memory limit is refused at its
!>    MESH card before it is generated; a run whose history would not fit is
!>    refused before it starts, with the estimate; the counts the estimator
!>    predicts match the generators; the overlap test is O(n) on a level-5 sphere.
program test_mesh_guards
  use, intrinsic :: iso_fortran_env, only: int64
  use visco2d_kinds, only: dp, pi
  use visco2d_error, only: error_t, error_text
  use visco2d_deck, only: deck_t, read_deck
  use visco2d_driver, only: run_deck
  use visco2d_record, only: record_t
  use visco2d_overlap, only: overlap_t, check_edges, check_overlaps, edge_keys, overlap_none, wedges_overlap
  use visco2d_sorting, only: sorted_order
  use visco2d_budget, only: run_size_t, parse_memory_size, set_memory_limit, memory_limit, bytes_text, count_text, &
                            seconds_text, sphere_mesh_counts, grid_mesh_counts, machine_memory, mesh_run_size
  use visco2d_estimate, only: estimate_run, check_run_size, long_run_note
  use visco2d_testing, only: check, check_close, check_text_contains, test_summary, write_deck, read_lines
  use visco2d_strings, only: integer_text
  use visco2d_test_decks, only: deck_line_length, square, try_read_deck, check_error_location
  implicit none

  character(*), parameter :: folder = 'build/test_decks/mesh_guards'
  character(*), parameter :: out_root = 'build/test_decks/mesh_guards_out'
  character(len=deck_line_length), allocatable :: lines(:)
  character(:), allocatable :: message

  call execute_command_line('rm -rf '//folder//' '//out_root)
  call execute_command_line('mkdir -p '//folder//' '//out_root)

  call set_memory_limit('8G', 'the test', message)
  call check('limit_set', len(message) == 0, message)

  ! ------------------------------------------------ numbers and generation (int64)
  lines = square()
  lines(5) = 'NODE 1 0 0 GEN=3 INC=999999999 DR=0.1'
  call expect_error('node_inc_overflow', lines, 5, 18, 'NODE', &
    'would number the last node 2,999,999,998, past the largest node number 999,999,999')

  lines = square()
  lines(5) = 'NODE 1 0 0 GEN=999999998 DR=1e-9'
  call expect_error('node_gen_count', lines, 5, 12, 'NODE', &
    'the mesh would have 999,999,999 nodes and 0 elements, more than 100,000,000')

  lines = square()
  lines(9) = 'ELEMENT 1 1 2 3 4 MAT=steel GEN=3 INC=999999999'
  call expect_error('element_inc_overflow', lines, 9, 35, 'ELEMENT', &
    'would number the last element 2,999,999,998, past the largest element number 999,999,999')

  lines = square()
  lines(9) = 'ELEMENT 1 1 2 3 4 MAT=steel GEN=1 NINC=999999999'
  call expect_error('element_ninc_overflow', lines, 9, 35, 'ELEMENT', &
    'would give element 2 node 1,000,000,000: node numbers must be in 1..999,999,999')

  lines = square()
  lines(9) = 'ELEMENT 1 1 2 3 4 MAT=steel GEN=1 NINC=-5'
  call expect_error('element_ninc_negative', lines, 9, 35, 'ELEMENT', &
    'would give element 2 node -4: node numbers must be in 1..999,999,999')

  lines = square()
  lines(9) = 'ELEMENT 1 1 2 3 4 MAT=steel GEN=200000000 NINC=0'
  call expect_error('element_gen_count', lines, 9, 29, 'ELEMENT', 'more than 100,000,000')

  lines = square()
  lines(9) = 'ELEMENT 1 1 -2 3 4 MAT=steel'
  call expect_error('element_node_negative', lines, 9, 13, 'ELEMENT', 'node numbers must be positive, got -2')

  ! A GEN within the count cap but whose mesh cannot fit the memory limit is
  ! refused at the card, before the arrays are made (here 1 GiB against 30
  ! million nodes: at least 64 bytes each for the stiffness alone).
  call set_memory_limit('1G', 'the test', message)
  lines = square()
  lines(5) = 'NODE 1 0 0 GEN=30000000 DR=1e-9'
  call expect_error('node_gen_memory', lines, 5, 12, 'NODE', 'a run on it needs at least')
  call set_memory_limit('8G', 'the test', message)

  ! --------------------------------------------------------- coordinates and scale
  lines = square()
  lines(6) = 'NODE 2 1e5 0'
  call expect_error('coordinate_out_of_range', lines, 6, 8, 'NODE', 'r = ')
  lines = square()
  lines(6) = 'NODE 2 1 0 GEN=2 DR=6000'
  call expect_error('generated_coordinate_out_of_range', lines, 6, 12, 'NODE', &
                    'the last generated r = ')
  lines = square()
  lines(6) = 'NODE 2 1e-10 0'
  lines(7) = 'NODE 3 1e-10 1e-10'
  lines(8) = 'NODE 4 0 1e-10'
  call expect_error('mesh_too_small', lines, 9, 1, 'ELEMENT', 'm across: lengths are in metres')

  ! ----------------------------------------------------------- degenerate elements
  lines = square()
  lines(7) = 'NODE 3 2 0'
  call expect_error('zero_area', lines, 9, 9, 'ELEMENT', 'element 1 has a non-positive Jacobian')
  lines = square()
  lines(9) = 'ELEMENT 1 1 4 3 2 MAT=steel'
  call expect_error('clockwise', lines, 9, 9, 'ELEMENT', 'number its nodes counter-clockwise')
  lines = square()
  lines(7) = 'NODE 3 1 1e-13'
  lines(8) = 'NODE 4 0 1e-13'
  call expect_error('nearly_flat', lines, 9, 9, 'ELEMENT', 'element 1 is nearly flat')

  ! -------------------------------------------------- elements covering area twice
  ! The same four nodes: accepted before, it made the body twice as stiff there.
  lines = block()
  lines = [character(len=deck_line_length) :: lines(1:11), 'ELEMENT 10 1 2 6 5 MAT=m', lines(12:)]
  call expect_error('coincident_elements', lines, 12, 9, 'ELEMENT', &
    'elements 1 (line 9) and 10 have the same four nodes (1 2 6 5)')
  lines = block()
  lines = [character(len=deck_line_length) :: lines(1:11), 'ELEMENT 10 6 5 1 2 MAT=m', lines(12:)]
  call expect_error('coincident_elements_rotated', lines, 12, 9, 'ELEMENT', &
    'elements 1 (line 9) and 10 have the same four nodes')

  ! A third element on the side 6-5 (below it, over element 1).
  lines = block()
  lines = [character(len=deck_line_length) :: lines(1:11), 'NODE 21 0.00 0.005', 'NODE 22 0.01 0.005', &
           'ELEMENT 10 6 5 21 22 MAT=m', lines(12:)]
  call expect_error('three_on_a_side', lines, 14, 9, 'ELEMENT', 'is shared by elements 1 (line 9), 4 (line 10) and 10')

  ! Both elements on the same side of their common side 3-4.
  lines = two_elements('NODE 5 0.2 0.5', 'NODE 6 0.8 0.5', 'ELEMENT 2 3 4 5 6 MAT=m')
  call expect_error('same_side', lines, 12, 9, 'ELEMENT', &
    'elements 1 (line 11) and 2 lie on the same side of their common side 3-4: they overlap')

  ! Overlapping areas, no node in common: inside, and across a corner.
  lines = two_elements('NODE 5 0.2 0.2', 'NODE 6 0.8 0.2', 'ELEMENT 2 5 6 7 8 MAT=m', &
                       'NODE 7 0.8 0.8', 'NODE 8 0.2 0.8')
  call expect_error('inside', lines, 14, 9, 'ELEMENT', 'element 2 overlaps element 1 (line 13): their areas intersect')
  lines = two_elements('NODE 5 0.5 0.5', 'NODE 6 1.5 0.5', 'ELEMENT 2 5 6 7 8 MAT=m', &
                       'NODE 7 1.5 1.5', 'NODE 8 0.5 1.5')
  call expect_error('across_corner', lines, 14, 9, 'ELEMENT', 'element 2 overlaps element 1 (line 13)')
  ! The same element again, on four new nodes at the same points: an overlap (not only a crack).
  lines = two_elements('NODE 5 0 0', 'NODE 6 1 0', 'ELEMENT 2 5 6 7 8 MAT=m', 'NODE 7 1 1', 'NODE 8 0 1')
  call expect_error('duplicate_on_new_nodes', lines, 14, 9, 'ELEMENT', 'element 2 overlaps element 1 (line 13)')

  ! Neighbours sharing a side, or only a corner, are fine.
  lines = two_elements('NODE 5 2 0', 'NODE 6 2 1', 'ELEMENT 2 2 5 6 3 MAT=m')
  call expect_valid('neighbours_share_a_side', lines)
  lines = two_elements('NODE 5 2 1', 'NODE 6 2 2', 'ELEMENT 2 3 5 6 7 MAT=m', 'NODE 7 1 2')
  call expect_valid('neighbours_share_a_corner', lines)

  ! A body with a hole (the centre element left out), and a second body in the hole: fine.
  lines = block()
  lines(10) = 'ELEMENT 4 5 6 10 9 MAT=m'
  lines = [character(len=deck_line_length) :: lines(1:10), 'ELEMENT 6 7 8 12 11 MAT=m', lines(11:)]
  call expect_valid('hole', lines)
  lines = [character(len=deck_line_length) :: lines(1:11), 'NODE 31 0.012 0.012', 'NODE 32 0.018 0.012', &
           'NODE 33 0.018 0.018', 'NODE 34 0.012 0.018', 'ELEMENT 40 31 32 33 34 MAT=m', lines(12:)]
  call expect_valid('body_in_the_hole', lines)
  ! A strip that turns back over its first element (sharing one node with it).
  lines = [character(len=deck_line_length) :: 'TITLE fold', 'ANALYSIS STATIC', 'GEOMETRY PLANESTRAIN', &
    'MATERIAL m ELASTIC E=5e6 NU=0.3', 'NODE 1 0 0', 'NODE 2 1 0', 'NODE 3 1 1', 'NODE 4 0 1', 'NODE 5 3 0', &
    'NODE 6 3 1', 'NODE 7 3 2', 'NODE 8 1 2', 'NODE 9 0 1.5', 'NODE 10 0 0.5', 'ELEMENT 1 1 2 3 4 MAT=m', &
    'ELEMENT 2 2 5 6 3 MAT=m', 'ELEMENT 3 3 6 7 8 MAT=m', 'ELEMENT 4 3 8 9 10 MAT=m', 'FIX 1 RZ', 'FIX 2 Z', 'END']
  call expect_error('fold', lines, 18, 9, 'ELEMENT', 'element 4 overlaps element 1 (line 15)')
  ! Folded further, on a new node: its last element lies across the first and the third.
  lines(13) = 'NODE 9 -0.5 1.5'
  lines(14) = 'NODE 10 -0.5 0.5'
  lines(18) = 'ELEMENT 4 11 8 9 10 MAT=m'
  lines = [character(len=deck_line_length) :: lines(1:14), 'NODE 11 1.2 0.8', lines(15:)]
  call expect_error('fold_apart', lines, 19, 9, 'ELEMENT', 'element 4 overlaps element ')

  ! ------------------------------------------------------ cracks and hanging nodes
  ! Two rows of nodes at z = 0.01 (5-8 and 17-20): the rows of elements are not joined.
  lines = block()
  lines(10) = 'ELEMENT 4 17 18 10 9 MAT=m GEN=2'
  lines = [character(len=deck_line_length) :: lines(1:11), 'NODE 17 0.00 0.01 GEN=3 DR=0.01', lines(12:)]
  call expect_error('crack', lines, 12, 6, 'NODE', 'are at the same point (r = ')
  ! Node 5 of the two upper elements lies inside the top side of the lower one.
  lines = [character(len=deck_line_length) :: 'TITLE hanging node', 'ANALYSIS STATIC', 'GEOMETRY PLANESTRAIN', &
    'MATERIAL m ELASTIC E=5e6 NU=0.3', 'NODE 1 0 0', 'NODE 2 2 0', 'NODE 3 2 1', 'NODE 4 0 1', 'NODE 5 1 1', &
    'NODE 6 1 2', 'NODE 7 0 2', 'NODE 8 2 2', 'ELEMENT 1 1 2 3 4 MAT=m', 'ELEMENT 2 4 5 6 7 MAT=m', &
    'ELEMENT 3 5 3 8 6 MAT=m', 'FIX 1 RZ', 'FIX 2 Z', 'END']
  call expect_error('hanging_node', lines, 0, 9, 'ELEMENT', &     ! elements 2 and 3 both hold node 5
    ' lies on a side of element 1 (line 13) but is not one of its nodes')

  call check_wedges()
  call check_estimator_counts()
  call check_memory_sizes()
  call check_mesh_refused_before_generation()
  call check_run_refused_over_limit()
  call check_long_run_note()
  call check_level5_cost()
  call check_shipped_decks()

  call test_summary('test_mesh_guards')

contains

  !> A 3 x 3 block of 0.01 m elements from generation cards (inputs/block_cards.inp).
  function block() result(deck_lines)
    character(len=deck_line_length), allocatable :: deck_lines(:)
    deck_lines = [character(len=deck_line_length) :: &
      'TITLE block', &                               ! 1
      'ANALYSIS STATIC', &                           ! 2
      'GEOMETRY PLANESTRAIN', &                      ! 3
      'MATERIAL m ELASTIC E=5e6 NU=0.3', &           ! 4
      'NODE  1 0.00 0.00 GEN=3 DR=0.01', &           ! 5
      'NODE  5 0.00 0.01 GEN=3 DR=0.01', &           ! 6
      'NODE  9 0.00 0.02 GEN=3 DR=0.01', &           ! 7
      'NODE 13 0.00 0.03 GEN=3 DR=0.01', &           ! 8
      'ELEMENT 1 1 2 6 5 MAT=m GEN=2', &             ! 9
      'ELEMENT 4 5 6 10 9 MAT=m GEN=2', &            ! 10
      'ELEMENT 7 9 10 14 13 MAT=m GEN=2', &          ! 11
      'FIX BOTTOM Z', &                              ! 12
      'FIX 1 R', &                                   ! 13
      'PRESSURE TOP P=1e5', &                        ! 14
      'END']                                         ! 15
  end function block

  !> The unit square (nodes 1-4 on lines 5-8) with nodes 5, 6 (lines 9, 10) and
  !> the optional 7, 8 (11, 12), then element 1 and the second element.
  function two_elements(node5, node6, element2, node7, node8) result(deck_lines)
    character(*), intent(in) :: node5, node6, element2
    character(*), intent(in), optional :: node7, node8
    character(len=deck_line_length), allocatable :: deck_lines(:)
    deck_lines = [character(len=deck_line_length) :: 'TITLE two elements', 'ANALYSIS STATIC', 'GEOMETRY PLANESTRAIN', &
      'MATERIAL m ELASTIC E=5e6 NU=0.3', 'NODE 1 0 0', 'NODE 2 1 0', 'NODE 3 1 1', 'NODE 4 0 1', node5, node6]
    if (present(node7)) deck_lines = [character(len=deck_line_length) :: deck_lines, node7]
    if (present(node8)) deck_lines = [character(len=deck_line_length) :: deck_lines, node8]
    deck_lines = [character(len=deck_line_length) :: deck_lines, 'ELEMENT 1 1 2 3 4 MAT=m', element2, &
                  'FIX 1 RZ', 'FIX 2 Z', 'END']
  end function two_elements

  function deck_path(name) result(path)
    character(*), intent(in) :: name
    character(:), allocatable :: path
    path = folder//'/'//name//'.inp'
  end function deck_path

  !> read_deck fails with `path:line:column: CARD: ...fragment...` (line or column 0: not checked).
  subroutine expect_error(name, deck_lines, line, column, card, fragment)
    character(*), intent(in) :: name, deck_lines(:), card, fragment
    integer, intent(in) :: line, column
    character(:), allocatable :: path, text
    logical :: refused
    path = deck_path(name)
    call try_read_deck(path, refused, text, deck_lines)
    call check(name//'_refused', refused, 'read_deck accepted '//path)
    if (.not. refused) return
    print '(a)', '  '//text
    call check_error_location(name, text, path, line, column, card, fragment)
  end subroutine expect_error

  subroutine expect_valid(name, deck_lines)
    character(*), intent(in) :: name, deck_lines(:)
    character(:), allocatable :: text
    logical :: refused
    call try_read_deck(deck_path(name), refused, text, deck_lines)
    if (refused) print '(a)', '  '//text
    call check(name//'_accepted', .not. refused)
  end subroutine expect_valid

  !> wedges_overlap on hand-made cases: wedges that touch do not overlap.
  subroutine check_wedges()
    real(dp), parameter :: quarter = 0.5_dp*pi
    integer :: a, b
    call wedges_overlap([0.0_dp, quarter, 2*quarter, 3*quarter], [quarter, quarter, quarter, quarter], a, b)
    call check('wedges_four_quarters', a == 0)
    call wedges_overlap([3*quarter, 0.0_dp], [quarter, quarter], a, b)
    call check('wedges_two_quarters', a == 0)
    call wedges_overlap([0.0_dp, 0.5_dp*quarter], [quarter, quarter], a, b)
    call check('wedges_overlapping', a == 1 .and. b == 2)
    call wedges_overlap([3.5_dp*quarter, 0.2_dp], [quarter, quarter], a, b)   ! across angle 0
    call check('wedges_overlapping_across_zero', a == 1 .and. b == 2)
    call wedges_overlap([(0.1_dp*a, a = 0, 19)], [(0.1_dp, a = 0, 19)], a, b)  ! 20 wedges: the sorted path
    call check('wedges_twenty_touching', a == 0)
    call wedges_overlap([(0.1_dp*a, a = 19, 0, -1)], [(0.11_dp, a = 0, 19)], a, b)
    call check('wedges_twenty_overlapping', a > 0)
  end subroutine check_wedges

  !> The counts the estimator predicts before generating match the generated meshes;
  !> its half-bandwidth is a lower bound (so a refusal before generation is sure).
  subroutine check_estimator_counts()
    type(deck_t) :: deck
    type(error_t), allocatable :: error
    integer(int64) :: nodes, elements, width
    integer :: level
    do level = 1, 5
      lines = sphere_deck(level)
      call write_deck(deck_path('sphere_level'//integer_text(level)), lines)
      call read_deck(deck_path('sphere_level'//integer_text(level)), deck, error)
      call check('sphere_level'//integer_text(level)//'_reads', .not. allocated(error))
      if (allocated(error)) return
      call sphere_mesh_counts(level, nodes, elements, width)
      call check('sphere_level'//integer_text(level)//'_nodes', nodes == deck%mesh%nnode, count_text(nodes))
      call check('sphere_level'//integer_text(level)//'_elements', elements == deck%mesh%nelem, count_text(elements))
      call check('sphere_level'//integer_text(level)//'_bandwidth_bound', width <= deck%mesh%half_bandwidth .and. &
        width >= deck%mesh%half_bandwidth - 2, count_text(width)//' against '//integer_text(deck%mesh%half_bandwidth))
    end do
    lines = rect_deck(7, 3)
    call write_deck(deck_path('rect_7x3'), lines)
    call read_deck(deck_path('rect_7x3'), deck, error)
    call check('rect_reads', .not. allocated(error))
    if (allocated(error)) return
    call grid_mesh_counts(7, 3, nodes, elements, width)
    call check('rect_nodes', nodes == deck%mesh%nnode)
    call check('rect_elements', elements == deck%mesh%nelem)
    call check('rect_bandwidth_bound', width <= deck%mesh%half_bandwidth, &
               count_text(width)//' against '//integer_text(deck%mesh%half_bandwidth))
  end subroutine check_estimator_counts

  function sphere_deck(level) result(deck_lines)
    integer, intent(in) :: level
    character(len=deck_line_length), allocatable :: deck_lines(:)
    deck_lines = [character(len=deck_line_length) :: 'TITLE sphere', 'ANALYSIS STATIC', &
      'MATERIAL m ELASTIC E=1e6 NU=0.3', 'MESH SPHERE R=0.0366 LEVEL='//integer_text(level), 'FIX BOTTOM Z', &
      'PRESSURE OUTER P=1e3', 'END']
  end function sphere_deck

  function rect_deck(nr, nz) result(deck_lines)
    integer, intent(in) :: nr, nz
    character(len=deck_line_length), allocatable :: deck_lines(:)
    deck_lines = [character(len=deck_line_length) :: 'TITLE rect', 'ANALYSIS STATIC', &
      'MATERIAL m ELASTIC E=1e6 NU=0.3', 'MESH RECT R0=0 R1=1 Z0=0 Z1=1 NR='//integer_text(nr)//' NZ='//integer_text(nz), &
      'FIX BOTTOM Z', 'PRESSURE TOP P=1e3', 'END']
  end function rect_deck

  !> Memory sizes as the user writes them, and as messages print them.
  subroutine check_memory_sizes()
    integer(int64) :: bytes
    logical :: ok
    real(dp) :: limit
    character(:), allocatable :: origin
    logical :: raisable
    call parse_memory_size('8G', bytes, ok)
    call check('size_8G', ok .and. bytes == 8_int64*1024_int64**3)
    call parse_memory_size('512m', bytes, ok)
    call check('size_512m', ok .and. bytes == 512_int64*1024_int64**2)
    call parse_memory_size('1.5GiB', bytes, ok)
    call check('size_1.5GiB', ok .and. bytes == 3_int64*512*1024_int64**2)
    call parse_memory_size('8GB', bytes, ok)
    call check('size_8GB', ok .and. bytes == 8_int64*1024_int64**3)
    call parse_memory_size('1000000', bytes, ok)
    call check('size_bytes', ok .and. bytes == 1000000_int64)
    call parse_memory_size(' 2T ', bytes, ok)
    call check('size_2T', ok .and. bytes == 2_int64*1024_int64**4)
    call parse_memory_size('0', bytes, ok)
    call check('size_zero_refused', .not. ok)
    call parse_memory_size('-1G', bytes, ok)
    call check('size_negative_refused', .not. ok)
    call parse_memory_size('8X', bytes, ok)
    call check('size_unit_refused', .not. ok)
    call parse_memory_size('1.2.3G', bytes, ok)
    call check('size_two_points_refused', .not. ok)
    call parse_memory_size('G', bytes, ok)
    call check('size_no_number_refused', .not. ok)
    call parse_memory_size('', bytes, ok)
    call check('size_empty_refused', .not. ok)
    call parse_memory_size('1e30', bytes, ok)
    call check('size_exponent_refused', .not. ok)
    call set_memory_limit('lots', '--max-memory', message)
    call check_text_contains('size_option_message', message, '--max-memory "lots" is not a memory size')
    call check('bytes_text_b', bytes_text(512.0_dp) == '512 B', bytes_text(512.0_dp))
    call check('bytes_text_kib', bytes_text(1536.0_dp) == '1.50 KiB', bytes_text(1536.0_dp))
    call check('bytes_text_gib', bytes_text(8.0_dp*1024.0_dp**3) == '8.00 GiB', bytes_text(8.0_dp*1024.0_dp**3))
    call check('bytes_text_huge', bytes_text(1.0e300_dp) == '> 1024 EiB', bytes_text(1.0e300_dp))
    call check('count_text', count_text(18006002_int64) == '18,006,002', count_text(18006002_int64))
    call check('count_text_small', count_text(999_int64) == '999', count_text(999_int64))
    call check('seconds_text_short', seconds_text(0.04_dp) == '0.1 s', seconds_text(0.04_dp))
    call check('seconds_text_minutes', seconds_text(600.0_dp) == '10 min', seconds_text(600.0_dp))
    ! The limit never exceeds the machine's memory, whatever the user asks.
    call set_memory_limit('1024T', 'the test', message)
    call memory_limit(limit, origin, raisable)
    if (machine_memory() > 0) then
      call check('limit_capped_by_machine', limit == real(machine_memory(), dp) .and. .not. raisable, origin)
      call check_text_contains('limit_capped_origin', origin, "this machine's memory")
    end if
    call set_memory_limit('8G', 'the test', message)
    call memory_limit(limit, origin, raisable)
    if (machine_memory() >= 8_int64*1024_int64**3) call check('limit_user', limit == 8.0_dp*1024.0_dp**3 .and. raisable, origin)
  end subroutine check_memory_sizes

  !> MESH RECT NR=3000 NZ=3000 (9 million elements) hung silently: it is now
  !> refused at its card, with the estimate, before the mesh is generated.
  subroutine check_mesh_refused_before_generation()
    real :: start, finish
    lines = rect_deck(3000, 3000)
    call cpu_time(start)
    call expect_error('rect_3000x3000', lines, 4, 31, 'MESH', &
      'MESH RECT makes 9,006,001 nodes and 9,000,000 elements: a run on it needs at least')
    call cpu_time(finish)
    call check('rect_3000x3000_refused_at_once', finish - start < 1.0, 'took '//integer_text(nint(1000*(finish - start)))//' ms')
    lines = rect_deck(3000, 3000)
    call expect_error('rect_3000x3000_limit_named', lines, 4, 0, 'MESH', &
      'more than the limit of 8.00 GiB set by the test (a coarser mesh, or raise the limit with --max-memory')
    call check_sparse_factor_counted()
  end subroutine check_mesh_refused_before_generation

  !> The least memory of a generated mesh counts CHOLMOD's factor (the default
  !> solver) before the grid is made: a ring whose band factor would fit the
  !> limit but whose sparse factor would not is refused at its card, and runs
  !> on with a SOLVER BAND card after it (a 3.2 million element ring had
  !> been generated, numbered and checked for 9 s, 97 s under the sanitizers,
  !> before the full estimate refused it).
  subroutine check_sparse_factor_counted()
    integer, parameter :: nr = 4999, nt = 8
    integer(int64) :: nodes, elements, least_width
    type(run_size_t) :: band, sparse
    real(dp) :: limit
    character(:), allocatable :: origin
    logical :: raisable
    call set_memory_limit('128M', 'the test', message)
    call memory_limit(limit, origin, raisable)
    call grid_mesh_counts(nr, nt, nodes, elements, least_width)
    band = mesh_run_size(nodes, elements, least_width)
    sparse = mesh_run_size(nodes, elements, least_width, sparse=.true.)
    ! CHOLMOD's factor as run_size counts it: 80 bytes per n log2(n), n = 2 x nodes, one band copy.
    call check_close('ring_sparse_factor', sparse%factor_bytes, &
                     80.0_dp*(2*nodes)*log(2.0_dp*nodes)/log(2.0_dp), 1.0e-12_dp)
    call check_close('ring_sparse_band', sparse%band_bytes, (2.0_dp*nodes)*(least_width + 1)*8, 1.0e-12_dp)
    call check('ring_limit_between', band%total_bytes < limit .and. limit < sparse%total_bytes, &
               bytes_text(band%total_bytes)//' < '//bytes_text(limit)//' < '//bytes_text(sparse%total_bytes))
    lines = ring_deck(nr, nt, '')
    call expect_error('ring_sparse_refused', lines, 4, 0, 'MESH', 'half-bandwidth at least '// &
                      integer_text(int(least_width))//', factored by CHOLMOD), more than the limit of 128 MiB')
    lines = ring_deck(nr, nt, 'SOLVER CHOLMOD')
    call expect_error('ring_cholmod_refused', lines, 4, 0, 'MESH', 'factored by CHOLMOD')
    lines = ring_deck(nr, nt, 'SOLVER BAND')
    call expect_valid('ring_band_fits', lines)
    lines = ring_deck(nr, nt, 'SOLVER NONE')          ! the SOLVER card's own error, not the memory
    call expect_error('ring_bad_solver', lines, 8, 8, 'SOLVER', 'solver must be BAND')
    call set_memory_limit('8G', 'the test', message)
  end subroutine check_sparse_factor_counted

  function ring_deck(nr, nt, solver_card) result(deck_lines)
    integer, intent(in) :: nr, nt
    character(*), intent(in) :: solver_card
    character(len=deck_line_length), allocatable :: deck_lines(:)
    deck_lines = [character(len=deck_line_length) :: 'TITLE ring', 'ANALYSIS STATIC', &
      'MATERIAL m ELASTIC E=1e6 NU=0.3', 'MESH RING R0=0.1 R1=0.2 NR='//integer_text(nr)//' NT='//integer_text(nt), &
      'FIX AXIS R', 'FIX BOTTOM Z', 'PRESSURE INNER P=1e3', solver_card, 'END']
  end function ring_deck

  !> A small mesh over a million steps with a history row each: the history
  !> table alone needs ~330 MiB. Over a 100 MiB limit the run is refused at
  !> the MESH card with the parts of the estimate, and leaves no output.
  subroutine check_run_refused_over_limit()
    type(deck_t) :: deck
    type(error_t), allocatable :: error
    type(record_t) :: record
    type(run_size_t) :: size
    character(:), allocatable :: text
    logical :: exists
    call write_deck(deck_path('million_steps'), million_steps())
    call read_deck(deck_path('million_steps'), deck, error)
    call check('million_steps_reads', .not. allocated(error))
    if (allocated(error)) return
    size = estimate_run(deck)
    call check('million_steps_steps', size%steps == 1000000_int64)
    call check('million_steps_rows', size%history_rows == 1000002_int64)
    call check_close('million_steps_history_bytes', size%history_bytes, 1000002.0_dp*(14 + 10)*8, 1.0e-12_dp)
    ! CHOLMOD (the default solver): one band matrix and its sparse factor, 80 bytes per n log2(n).
    call check_close('million_steps_band_bytes', size%band_bytes, 1.0_dp*212*(35 + 1)*8, 1.0e-12_dp)
    call check_close('million_steps_factor_bytes', size%factor_bytes, 80.0_dp*212*log(212.0_dp)/log(2.0_dp), 1.0e-12_dp)
    ! Writing results.h5: the history table in the record, and twice (buffer 1.125 x, and its copy) in results.h5.
    call check('million_steps_write_peak', size%total_bytes == size%write_bytes .and. &
               size%image_bytes > 2.1_dp*size%history_bytes, bytes_text(size%image_bytes))
    call set_memory_limit('100M', 'the test', message)
    call check_run_size(deck, size, error)
    call check('million_steps_refused', allocated(error))
    if (allocated(error)) then
      text = error_text(error)
      print '(a)', '  '//text
      call check_text_contains('million_steps_located', text, deck_path('million_steps')//':4:1: MESH: ')
      call check_text_contains('million_steps_history_named', text, 'history table')
      call check_text_contains('million_steps_advice', text, 'a larger OUTPUT EVERY= or fewer steps')
    end if
    call run_deck(deck_path('million_steps'), out_root, record, error)
    call check('million_steps_run_refused', allocated(error))
    inquire(file=out_root//'/million_steps/summary.txt', exist=exists)
    call check('million_steps_no_output', .not. exists)
    call set_memory_limit('8G', 'the test', message)
  end subroutine check_run_refused_over_limit

  !> Table 1 at level 1 with DT = 1e-9 s to 1 ms: the deck of the issue.
  function million_steps() result(deck_lines)
    character(len=deck_line_length), allocatable :: deck_lines(:)
    deck_lines = [character(len=deck_line_length) :: 'TITLE a million steps', 'ANALYSIS DYNAMIC', &
      'MATERIAL apple ELASTIC E=18.11e6 NU=0.219 RHO=756.85', 'MESH SPHERE R=0.0366 LEVEL=1', &
      'INITIAL VZ=-0.9982', 'TIME DT=1e-9 TEND=1e-3', 'OUTPUT EVERY=1', 'FIX BOTTOM Z', 'PROBE pole R=0 Z=0', 'END']
  end function million_steps

  !> A run estimated past 20 s gets a one-line note with its size; a short one none.
  subroutine check_long_run_note()
    type(deck_t) :: deck
    type(error_t), allocatable :: error
    character(:), allocatable :: note
    call read_deck(deck_path('million_steps'), deck, error)
    if (allocated(error)) return
    note = long_run_note('deck.inp', estimate_run(deck))
    call check_text_contains('note_long', note, 'visco2d: note: deck.inp: a long run, roughly ')
    call check_text_contains('note_size', note, '1,000,000 steps of 212 equations, half-bandwidth 35')
    call read_deck(deck_path('sphere_level1'), deck, error)
    if (allocated(error)) return
    note = long_run_note('deck.inp', estimate_run(deck))
    call check('note_short_none', len(note) == 0, note)
  end subroutine check_long_run_note

  !> The overlap tests on the level-5 sphere (22,528 elements): the candidate
  !> tests grow as n, and their time is a small part of reading the deck.
  subroutine check_level5_cost()
    type(deck_t) :: deck
    type(error_t), allocatable :: error
    type(overlap_t) :: finding
    integer(int64), allocatable :: keys(:)
    integer, allocatable :: order(:)
    integer(int64) :: pairs, clock0, clock1, clock2, rate
    real(dp) :: read_seconds, check_seconds
    call system_clock(clock0, rate)
    call read_deck(deck_path('sphere_level5'), deck, error)
    call system_clock(clock1)
    if (allocated(error)) return
    keys = edge_keys(deck%mesh%connectivity, deck%mesh%nnode)
    order = sorted_order(keys)
    call check_edges(deck%mesh%connectivity, keys, order, finding)
    call check('level5_edges_clean', finding%kind == overlap_none)
    call check_overlaps(deck%mesh%xy, deck%mesh%connectivity, keys, order, 1.0e-9_dp*deck%mesh%size, finding, pairs)
    call system_clock(clock2)
    call check('level5_no_overlap', finding%kind == overlap_none)
    call check('level5_work_linear', pairs <= 8_int64*deck%mesh%nelem, &
               count_text(pairs)//' tests for '//integer_text(deck%mesh%nelem)//' elements')
    read_seconds = real(clock1 - clock0, dp)/rate
    check_seconds = real(clock2 - clock1, dp)/rate
    print '(a, i0, a, i0, a, es9.2, a, es9.2, a)', '# level 5: ', deck%mesh%nelem, ' elements, ', pairs, &
      ' candidate tests; read_deck ', read_seconds, ' s (checks included), the edge and overlap checks ', &
      check_seconds, ' s'
  end subroutine check_level5_cost

  !> No shipped deck trips a mesh check (no false alarm).
  subroutine check_shipped_decks()
    character(*), parameter :: list = 'build/test_decks/mesh_guards_inputs.txt'
    character(:), allocatable :: paths(:)
    type(deck_t) :: deck
    type(error_t), allocatable :: error
    logical :: found
    integer :: k
    call execute_command_line('ls inputs/*.inp > '//list)
    call read_lines(list, paths, found, delete=.true.)
    call check('inputs_listed', found)
    if (.not. found) return
    do k = 1, size(paths)
      call read_deck(trim(paths(k)), deck, error)
      if (allocated(error)) print '(a)', '  '//error_text(error)
      call check('input_reads_'//trim(paths(k)), .not. allocated(error))
      if (allocated(error)) deallocate(error)
    end do
    call check('inputs_found', size(paths) >= 10, integer_text(size(paths))//' decks')
  end subroutine check_shipped_decks
end program test_mesh_guards
