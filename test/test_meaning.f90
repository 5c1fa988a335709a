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
  use visco2d_strings, only: itoa
  use visco2d_testing, only: check, check_text_contains, test_summary, write_deck
  use visco2d_test_decks, only: deck_line_length, impact, press, try_read_deck, check_error_location
  implicit none

  character(*), parameter :: folder = 'build/test_decks/meaning'
  character(*), parameter :: out_root = 'build/test_decks/meaning_out'

  call execute_command_line('rm -rf '//folder//' '//out_root)
  call execute_command_line('mkdir -p '//folder//' '//out_root)

  call fix_on_the_plate()
  call probe_outside()
  call fields_after_the_stop()

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
    call check(name//'_warnings', found == expected, itoa(found)//' warning(s) holding "'//fragment// &
               '", expected '//itoa(expected)//' (of '//itoa(total)//'): '//text)
    if (found > 0 .and. present(line) .and. present(card)) &
      call check_text_contains(name//'_located', text, deck_path(name)//':'//itoa(line)//': '//card//': ')
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
      if (index(summary_value(record, 'warning_'//itoa(k)), deck_path('fields_late')//':10: OUTPUT: 2 FIELDS time(s) '// &
                'from 0.007 s on not written') == 1) found = found + 1
    end do
    call check('fields_late_warned', found == 1, itoa(found)//' OUTPUT warning_N key(s)')
    call check('fields_late_counted', summary_value(record, 'warnings') == '1', &
               'warnings = '//summary_value(record, 'warnings'))
  end subroutine fields_after_the_stop
end program test_meaning
