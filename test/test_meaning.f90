!> Inputs that ran with a meaning the user did not intend ("never a silent
!> wrong answer", round 3): each is now refused or warned about, the warning
!> located (file:line: CARD: text) and counted in the summary's `warnings`.
!> - a FIX of u_z on a node on the plate (q_max_MPa = 0 with force_max_N = 199);
!> - a PROBE point far outside the body (it read the nearest node, silently);
!> - OUTPUT FIELDS= times after a STOP AT= stop (no snapshot, silently);
!> - the decks of doc/robustness.md's "meaning" warnings (DROP with a gap,
!>   VR in axisymmetry, unit slips, a static deck without load, ...);
!> - a deck that misses its own EXPECT cards is reported (exit status 3).
program test_meaning
  use visco2d_kinds, only: dp
  use visco2d_error, only: error_t, error_text
  use visco2d_deck, only: deck_t, read_deck
  use visco2d_driver, only: run_deck
  use visco2d_expect, only: summary_value, expect_tally_t
  use visco2d_record, only: record_t
  use visco2d_strings, only: integer_text
  use visco2d_testing, only: check, check_text_contains, test_summary, write_deck
  use visco2d_test_decks, only: deck_line_length, impact, press, square, creep, dynamic, try_read_deck, &
                                check_error_location
  implicit none

  character(*), parameter :: folder = 'build/test_decks/meaning'
  character(*), parameter :: out_root = 'build/test_decks/meaning_out'

  call execute_command_line('rm -rf '//folder//' '//out_root)
  call execute_command_line('mkdir -p '//folder//' '//out_root)

  call fix_on_the_plate()
  call probe_outside()
  call fields_after_the_stop()
  call drop_with_a_gap()
  call motion_on_the_axis()
  call unit_slips()
  call static_without_load()
  call sphere_in_plane_strain()
  call unused_material()
  call misleading_messages()

  call execute_command_line('rm -rf '//out_root)
  call test_summary('test_meaning')

contains

  !> The deck path of a case.
  function deck_path(name) result(path)
    character(*), intent(in) :: name
    character(:), allocatable :: path
    path = folder//'/'//name//'.inp'
  end function deck_path

  !> The text of an error ('' if none).
  function error_or_nothing(error) result(text)
    type(error_t), allocatable, intent(in) :: error
    character(:), allocatable :: text
    text = ''
    if (allocated(error)) text = error_text(error)
  end function error_or_nothing

  !> `deck_lines` with `card` inserted before the last line (END).
  function with_card(deck_lines, card) result(lines)
    character(*), intent(in) :: deck_lines(:), card
    character(len=deck_line_length), allocatable :: lines(:)
    lines = [character(len=deck_line_length) :: deck_lines(:size(deck_lines) - 1), card, deck_lines(size(deck_lines))]
  end function with_card

  !> Read the deck (written from deck_lines): it must read, and its warnings
  !> that contain `fragment` are counted into `found` (all of them into `total`).
  subroutine read_warnings(name, deck_lines, fragment, found, total, text)
    character(*), intent(in) :: name, deck_lines(:), fragment
    integer, intent(out) :: found, total
    character(:), allocatable, intent(out) :: text     !< the first warning holding `fragment` ('' if none)
    type(deck_t) :: deck
    type(error_t), allocatable :: error
    integer :: k
    found = 0
    total = 0
    text = ''
    call write_deck(deck_path(name), deck_lines)
    call read_deck(deck_path(name), deck, error)
    call check(name//'_reads', .not. allocated(error), 'refused: '//error_or_nothing(error))
    if (allocated(error)) return
    total = size(deck%warnings)
    do k = 1, size(deck%warnings)
      if (index(deck%warnings(k)%text, fragment) == 0) cycle
      found = found + 1
      if (len(text) == 0) text = deck%warnings(k)%text
    end do
  end subroutine read_warnings

  !> A deck must read with exactly `expected` warnings holding `fragment`,
  !> the first located at `line` of card `card`.
  subroutine expect_warning(name, deck_lines, fragment, expected, line, card)
    character(*), intent(in) :: name, deck_lines(:), fragment
    integer, intent(in) :: expected
    integer, intent(in), optional :: line
    character(*), intent(in), optional :: card
    integer :: found, total
    character(:), allocatable :: text
    call read_warnings(name, deck_lines, fragment, found, total, text)
    call check(name//'_warnings', found == expected, integer_text(found)//' warning(s) holding "'//fragment// &
               '", expected '//integer_text(expected)//' (of '//integer_text(total)//'): '//text)
    if (found > 0 .and. present(line) .and. present(card)) &
      call check_text_contains(name//'_located', text, deck_path(name)//':'//integer_text(line)//': '//card//': ')
  end subroutine expect_warning

  ! ------------------------------------------------------------------ cases

  !> A FIX of u_z on the contact pole took the plate's force at that node:
  !> the Table-1 impact with FIX BOTTOM Z ran (exit 0) with q_max_MPa = 0 and
  !> force_max_N = 199. Refused at the FIX card; FIX AXIS R and a FIX of
  !> the top (off the plate) still run.
  subroutine fix_on_the_plate()
    logical :: refused
    character(:), allocatable :: text
    character(len=deck_line_length), allocatable :: lines(:)
    lines = with_card(impact(), 'FIX BOTTOM Z')            ! line 10
    call try_read_deck(deck_path('fix_pole'), refused, text, lines)
    call check('fix_pole_refused', refused, 'read_deck accepted FIX BOTTOM Z on the plate')
    if (refused) call check_error_location('fix_pole', text, deck_path('fix_pole'), 10, 1, 'FIX', &
                                           'lies on the plate')
    lines = with_card(press(), 'FIX BOTTOM RZ')            ! static contact: line 8
    call try_read_deck(deck_path('fix_pole_static'), refused, text, lines)
    call check('fix_pole_static_refused', refused, 'read_deck accepted FIX BOTTOM RZ on the plate')
    if (refused) call check_error_location('fix_pole_static', text, deck_path('fix_pole_static'), 8, 1, 'FIX', &
                                           'the plate already holds the body in z')
    call try_read_deck(deck_path('fix_axis'), refused, text, with_card(impact(), 'FIX AXIS R'))
    call check('fix_axis_r_runs', .not. refused, text)
    call try_read_deck(deck_path('fix_top'), refused, text, with_card(impact(), 'FIX TOP Z'))
    call check('fix_top_z_reads', .not. refused, text)
  end subroutine fix_on_the_plate

  !> PROBE far R=0 Z=1.4 on a 38 mm sphere read node at the top, silently;
  !> so did a point 10 mm below the plate. A point inside the body, on a
  !> node, or on the true sphere (outside its polygon by the sagitta of a
  !> side) does not warn.
  subroutine probe_outside()
    real(dp), parameter :: radius = 0.0381_dp     ! impact()'s sphere
    character(len=60) :: on_sphere
    call expect_warning('probe_far', with_card(impact(), 'PROBE far R=0 Z=1.4'), 'lies outside the body', 1, &
                        10, 'PROBE')
    call expect_warning('probe_below', with_card(impact(), 'PROBE below R=0 Z=-0.01'), 'lies outside the body', 1, &
                        10, 'PROBE')
    call expect_warning('probe_pole', with_card(impact(), 'PROBE pole R=0 Z=0'), 'PROBE', 0)
    call expect_warning('probe_centre', with_card(impact(), 'PROBE centre R=0 Z=0.0381'), 'PROBE', 0)
    write(on_sphere, '(a, es22.15, a, es22.15)') 'PROBE side R=', radius*sin(0.7_dp), ' Z=', &
      radius*(1.0_dp - cos(0.7_dp))
    call expect_warning('probe_on_sphere', with_card(impact(), trim(on_sphere)), 'PROBE', 0)
    call expect_warning('probe_node', with_card(impact(), 'PROBE top NODE=1'), 'PROBE', 0)
  end subroutine probe_outside

  !> OUTPUT FIELDS= times after a STOP AT=MAXDEFORMATION stop (before TEND)
  !> were not written, silently: a run-time warning at the OUTPUT card, in
  !> `warnings` and as a warning_N key. A FIELDS time before the stop is written.
  subroutine fields_after_the_stop()
    character(len=deck_line_length), allocatable :: lines(:)
    type(record_t) :: record
    type(error_t), allocatable :: error
    integer :: k, found
    lines = impact()
    lines(9) = 'TIME DT=1e-5 TEND=8e-3'
    lines = with_card(lines, 'OUTPUT EVERY=10 FIELDS=1e-4,7e-3,7.5e-3')     ! line 10
    call write_deck(deck_path('fields_late'), lines)
    call run_deck(deck_path('fields_late'), out_root, record, error)
    call check('fields_late_runs', .not. allocated(error), error_or_nothing(error))
    if (allocated(error)) return
    call check('fields_late_stopped_early', summary_value(record, 'stop_reason') /= 'end of time', &
               'stop_reason = '//summary_value(record, 'stop_reason'))
    found = 0
    do k = 1, 20
      if (index(summary_value(record, 'warning_'//integer_text(k)), deck_path('fields_late')//':10: OUTPUT: 2 FIELDS time(s) '// &
                'from 0.007 s on not written') == 1) found = found + 1
    end do
    call check('fields_late_warned', found == 1, integer_text(found)//' OUTPUT warning_N key(s)')
    call check('fields_late_counted', summary_value(record, 'warnings') == '1', &
               'warnings = '//summary_value(record, 'warnings'))
  end subroutine fields_after_the_stop

  !> DROP HEIGHT=0.05 with the sphere 10 mm above the plate, in gravity: it
  !> struck at sqrt(2 g 0.06) = 1.084 m/s, not the 0.990 m/s of the card.
  !> A gap of 1 % of the height changes the speed by 0.5 %: the threshold.
  subroutine drop_with_a_gap()
    character(len=deck_line_length), allocatable :: lines(:)
    lines = impact()
    lines(6) = 'DROP HEIGHT=0.05'
    lines = with_card(lines, 'GRAVITY G=9.8')
    call expect_warning('drop_on_the_plate', lines, 'above the plate', 0)
    lines(7) = 'PLATE Z=-0.01'
    call expect_warning('drop_gap', lines, 'falls HEIGHT + gap = 6.0000E-02 m and strikes at 1.0844E+00 m/s', 1, &
                        6, 'DROP')
    lines(7) = 'PLATE Z=-0.0004'                           ! 0.8 % of the height: within the 0.5 % of speed
    call expect_warning('drop_small_gap', lines, 'above the plate', 0)
  end subroutine drop_with_a_gap

  !> INITIAL VR= in axisymmetry swells every ring; FR= on the axis acts on
  !> a held degree of freedom. In plane strain VR is a sideways throw.
  subroutine motion_on_the_axis()
    character(len=deck_line_length), allocatable :: lines(:)
    lines = impact()
    lines(6) = 'INITIAL VZ=-1 VR=0.5'
    call expect_warning('initial_vr_axisymmetric', lines, 'breathing motion', 1, 6, 'INITIAL')
    lines = dynamic()
    lines(3) = 'GEOMETRY PLANESTRAIN'
    lines(6) = 'INITIAL VZ=-1 VR=0.5'
    call expect_warning('initial_vr_plane_strain', lines, 'breathing', 0)
    call expect_warning('force_fr_on_axis', with_card(creep(), 'FORCE 1 FR=1'), 'does nothing', 1, 11, 'FORCE')
    call expect_warning('force_fz_on_axis', with_card(creep(), 'FORCE 1 FZ=1'), 'does nothing', 0)
  end subroutine motion_on_the_axis

  !> RHO=0.8 (g/cm^3 for 800 kg/m^3), R=38.1 (mm for 0.0381 m), a pad of 10 m.
  subroutine unit_slips()
    character(len=deck_line_length), allocatable :: lines(:)
    lines = impact()
    lines(4) = 'MATERIAL apple ELASTIC E=6e6 NU=0.3 RHO=0.8'
    call expect_warning('density_in_g_cm3', lines, 'in g/cm^3 that would be 8.0000E+02 kg/m^3', 1, 4, 'MATERIAL')
    call expect_warning('density_kg_m3', impact(), 'g/cm^3', 0)
    lines = impact()
    lines(5) = 'MESH SPHERE R=38.1 LEVEL=1'
    call expect_warning('radius_in_mm', lines, 'larger than any fruit', 1, 5, 'MESH')
    call expect_warning('radius_in_m', impact(), 'larger than any fruit', 0)
    lines = impact()
    lines(5) = 'MESH SPHERE R=0.0381 LEVEL=1 MAT=apple'
    lines = with_card(lines, 'MATERIAL foam ELASTIC E=1e5 NU=0.3 RHO=100')
    call expect_warning('pad_in_mm', with_card(lines, 'PAD THICKNESS=10 MAT=foam'), 'thicker than any handling pad', &
                        1, 11, 'PAD')
    call expect_warning('pad_in_m', with_card(lines, 'PAD THICKNESS=0.01 MAT=foam'), 'thicker than any', 0)
  end subroutine unit_slips

  !> A STATIC deck with supports and no load ran to zero everywhere.
  subroutine static_without_load()
    call expect_warning('static_no_load', square(), 'without any load', 1, 2, 'ANALYSIS')
    call expect_warning('static_force', with_card(square(), 'FORCE 3 FZ=-1'), 'without any load', 0)
    call expect_warning('static_prescribed', with_card(square(), 'FIX 3 Z UZ=-1e-4'), 'without any load', 0)
    call expect_warning('static_gravity', press(), 'without any load', 0)
  end subroutine static_without_load

  !> MESH SPHERE in GEOMETRY PLANESTRAIN is a long cylinder: said.
  subroutine sphere_in_plane_strain()
    character(len=deck_line_length), allocatable :: lines(:)
    lines = impact()
    lines(3) = 'GEOMETRY PLANESTRAIN'
    call expect_warning('sphere_plane_strain', lines, 'cross-section of a long cylinder', 1, 5, 'MESH')
    call expect_warning('sphere_axisymmetric', impact(), 'long cylinder', 0)
  end subroutine sphere_in_plane_strain

  !> A second MATERIAL no element names (a MAT= naming the other by mistake).
  subroutine unused_material()
    call expect_warning('unused_material', with_card(square(), 'MATERIAL rubber ELASTIC E=1e6 NU=0.4'), &
                        'material RUBBER is used by no element', 1, 12, 'MATERIAL')
    call expect_warning('used_material', with_card(square(), 'FORCE 3 FZ=-1'), 'used by no element', 0)
  end subroutine unused_material

  !> CORE=0.94 on GRID=LEGACY said "number its nodes counter-clockwise" (the
  !> user numbered none); E= with G= said "unknown field G".
  subroutine misleading_messages()
    logical :: refused
    character(:), allocatable :: text
    character(len=deck_line_length), allocatable :: lines(:)
    lines = impact()
    lines(5) = 'MESH SPHERE R=0.0381 LEVEL=1 GRID=LEGACY CORE=0.94'
    call try_read_deck(deck_path('legacy_core'), refused, text, lines)
    call check('legacy_core_refused', refused, 'read_deck accepted CORE=0.94 on GRID=LEGACY at level 1')
    if (refused) call check_error_location('legacy_core', text, deck_path('legacy_core'), 5, 42, 'MESH', &
      'the grid folds: element ')
    if (refused) call check('legacy_core_not_numbering', index(text, 'counter-clockwise') == 0, text)
    lines = impact()
    lines(4) = 'MATERIAL apple ELASTIC E=6e6 NU=0.3 G=2e6 RHO=800'
    call try_read_deck(deck_path('e_with_g'), refused, text, lines)
    call check('e_with_g_refused', refused, 'read_deck accepted E=, NU= and G=')
    if (refused) call check_error_location('e_with_g', text, deck_path('e_with_g'), 4, 37, 'MATERIAL', &
      'give the elastic constants one way: E= and NU=, or G= and K=')
    lines(4) = 'MATERIAL apple ELASTIC E=6e6 K=5e6 RHO=800'
    call try_read_deck(deck_path('e_with_k'), refused, text, lines)
    call check('e_with_k_refused', refused, 'read_deck accepted E= and K=')
    if (refused) call check_error_location('e_with_k', text, deck_path('e_with_k'), 4, 30, 'MATERIAL', &
      'give the elastic constants one way')
  end subroutine misleading_messages

end program test_meaning
