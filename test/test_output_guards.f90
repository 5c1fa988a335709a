!> What reaches the outputs, and faults while writing them:
!> - the last check before writing (visco2d_output_check) refuses a NaN or an
!>   Infinity anywhere an output would hold it (summary, history, snapshot
!>   fields, the deck numbers the listing echoes) and says where it is and
!>   which analysis or card it came from; user text ('NaN' as a title) passes;
!> - EXPECT: the relative error never overflows, an expected 0 or a second card
!>   for one key is refused at the card, the checks are counted per card;
!> - the writers report a failed write (/dev/full, a missing folder) instead of
!>   leaving a short file behind;
!> - the output root is checked before any run (empty, through a file, not
!>   creatable) and is not created by the check;
!> - stale `.partial.<host>.<pid>` / `.old.<host>.<pid>` folders of dead runs of
!>   this host are removed (an old folder is put back when its case folder is
!>   missing), those of live processes, of another host, or of a case whose lock
!>   is held kept; a case lock held refuses a second lock of that case;
!> - run-time warnings (record_warn) are located like the deck's and listed.
program test_output_guards
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_positive_inf, ieee_negative_inf, &
                                           ieee_is_finite
  use visco2d_kinds, only: dp
  use visco2d_strings, only: table_real, integer_text
  use visco2d_error, only: error_t
  use visco2d_deck, only: deck_t, read_deck
  use visco2d_record, only: record_t, snapshot_t, record_put, record_put_real, history_define, history_append, &
                            record_add_snapshot, record_warn
  use visco2d_output, only: write_summary, write_history, write_results_h5
  use visco2d_listing, only: write_listing
  use visco2d_output_check, only: check_finite_outputs, finite_text
  use visco2d_driver, only: run_deck, run_warning_count
  use visco2d_expect, only: relative_error, expect_tally_t, run_line, summary_value
  use visco2d_case_folder, only: prepare_output_root, remove_stale_folders, lock_case, unlock_case, case_lock_t
  use visco2d_system, only: make_directory, directory_exists, path_exists, process_id, process_alive, remove_tree, &
                            host_name
  use visco2d_testing, only: check, check_text_contains, test_summary, write_deck, message_of, read_lines
  implicit none

  character(*), parameter :: folder = 'build/test_output_guards'
  character(len=80), parameter :: block_deck(8) = [character(len=80) :: &
    'TITLE block', &
    'ANALYSIS STATIC', &
    'GEOMETRY PLANESTRAIN', &
    'MATERIAL steel ELASTIC E=200e9 NU=0.3', &
    'MESH RECT R0=0 R1=1 Z0=0 Z1=1 NR=2 NZ=2', &
    'FIX BOTTOM RZ', &
    'PRESSURE TOP P=1e6', &
    'END']
  real(dp) :: nan, infinity

  nan = ieee_value(1.0_dp, ieee_quiet_nan)
  infinity = ieee_value(1.0_dp, ieee_positive_inf)
  call remove_tree(folder)
  if (make_directory(folder) /= 0) error stop 'cannot create '//folder
  call write_deck(folder//'/block.inp', block_deck)

  call test_finite_text()
  call test_results_guard()
  call test_deck_numbers_guard()
  call test_relative_error()
  call test_expect_cards()
  call test_non_finite_run()
  call test_writers()
  call test_output_root()
  call test_stale_folders()
  call test_run_warnings()
  call test_summary('test_output_guards')

contains

  !> Summary values: numbers that are not finite are caught, words are text.
  subroutine test_finite_text()
    character(len=24), parameter :: bad(6) = [character(len=24) :: 'NaN', '-Infinity', 'inf', '+INF', &
                                              '1.0 NaN', '(1.0, Infinity)']
    character(len=32), parameter :: good(7) = [character(len=32) :: '1.500000000E+003', '0', &
      'maximum deformation', '0.1.0', 'inertia contact gravity', '-2.5E-300', 'infinite plate (none)']
    integer :: k
    do k = 1, size(bad)
      call check('finite_text_refuses_'//trim(bad(k)), .not. finite_text(trim(bad(k))))
    end do
    do k = 1, size(good)
      call check('finite_text_accepts_'//trim(good(k)), finite_text(trim(good(k))))
    end do
    call check('finite_text_accepts_empty', finite_text(''))
  end subroutine test_finite_text

  !> A small valid record for the block deck: summary, three history rows, one snapshot.
  subroutine clean_record(deck, record)
    type(deck_t), intent(in) :: deck
    type(record_t), intent(out) :: record
    type(snapshot_t) :: snapshot
    integer :: n
    n = deck%mesh%nnode
    call record_put(record, 'case', 'block')
    call record_put(record, 'title', 'NaN')                   ! the user's text, not a number
    call record_put(record, 'stop_reason', 'maximum deformation')
    call record_put_real(record, 'max_displacement_m', 1.0e-3_dp)
    call history_define(record, [character(len=16) :: 'step', 't_ms', 'alpha_mm'])
    call history_append(record, [0.0_dp, 0.0_dp, 0.0_dp])
    call history_append(record, [1.0_dp, 0.1_dp, 0.2_dp])
    call history_append(record, [2.0_dp, 0.2_dp, 0.4_dp])
    snapshot%name = 'step_000002'
    snapshot%label = 'final'
    snapshot%time = 2.0e-4_dp
    allocate(snapshot%displacement(2, n), snapshot%stress(4, n), snapshot%max_shear(n), snapshot%von_mises(n))
    allocate(snapshot%stress_gauss(4, 4, deck%mesh%nelem))
    snapshot%displacement = 0.0_dp
    snapshot%stress = 0.0_dp
    snapshot%max_shear = 0.0_dp
    snapshot%von_mises = 0.0_dp
    snapshot%stress_gauss = 0.0_dp
    call record_add_snapshot(record, snapshot)
  end subroutine clean_record

  subroutine test_results_guard()
    type(deck_t) :: deck
    type(record_t) :: record
    type(error_t), allocatable :: error
    character(:), allocatable :: text
    call read_deck(folder//'/block.inp', deck, error)
    call check('guard_deck_reads', .not. allocated(error))
    if (allocated(error)) return

    call clean_record(deck, record)
    call check_finite_outputs(deck, record, error)
    call check('guard_clean_record_passes', .not. allocated(error), 'error: '//message_of(error))

    call record_put_real(record, 'max_displacement_m', nan)
    call check_finite_outputs(deck, record, error)
    text = message_of(error)
    call check('guard_summary_nan_refused', allocated(error))
    call check_text_contains('guard_summary_nan_located', text, folder//'/block.inp:2: ANALYSIS: ')
    call check_text_contains('guard_summary_nan_names_analysis', text, 'the STATIC analysis produced a non-finite')
    call check_text_contains('guard_summary_nan_names_key', text, 'summary key max_displacement_m = NaN')

    call clean_record(deck, record)
    call record_put_real(record, 'hertz_alpha_max_mm', infinity)
    call check_finite_outputs(deck, record, error)
    call check_text_contains('guard_hertz_infinity_names_reference', message_of(error), &
                             'the Hertz reference of the STATIC analysis produced a non-finite result: '// &
                             'summary key hertz_alpha_max_mm = Infinity')

    call clean_record(deck, record)
    record%history(3, 2) = -infinity
    call check_finite_outputs(deck, record, error)
    call check_text_contains('guard_history_names_cell', message_of(error), &
      'history column alpha_mm = -Infinity in row 2 of 3 (step 1, t_ms = 1.000000000E-001)')

    call clean_record(deck, record)
    record%snapshots(1)%stress(2, 5) = nan
    call check_finite_outputs(deck, record, error)
    call check_text_contains('guard_snapshot_names_field', message_of(error), &
      'field stress of snapshot step_000002 (final) at t = 2.000000000E-004 s = NaN at node '// &
      integer_text(deck%mesh%node_id(5))//', component 2')

    call clean_record(deck, record)
    record%snapshots(1)%stress_gauss(1, 3, 2) = infinity
    call check_finite_outputs(deck, record, error)
    call check_text_contains('guard_gauss_names_element', message_of(error), &
      'field stress_gauss of snapshot step_000002 (final) at t = 2.000000000E-004 s = Infinity at element '// &
      integer_text(deck%mesh%element_id(2))//', Gauss point 3, component 1')

    call clean_record(deck, record)
    record%snapshots(1)%time = nan
    call check_finite_outputs(deck, record, error)
    call check_text_contains('guard_snapshot_time', message_of(error), 'the time of snapshot step_000002 (final) = NaN')
  end subroutine test_results_guard

  !> The deck's numbers the listing echoes: located at their card.
  subroutine test_deck_numbers_guard()
    type(deck_t) :: deck
    type(record_t) :: record
    type(error_t), allocatable :: error
    call read_deck(folder//'/block.inp', deck, error)
    if (allocated(error)) return
    call clean_record(deck, record)
    deck%materials(1)%bulk = infinity
    record%history(3, 2) = nan          ! the input is reported first: it explains the result
    call check_finite_outputs(deck, record, error)
    call check_text_contains('guard_material_located', message_of(error), &
      folder//'/block.inp:4: MATERIAL: the bulk modulus K of material STEEL is Infinity')
    call read_deck(folder//'/block.inp', deck, error)
    deck%loads%pressures(1)%value = -infinity
    call check_finite_outputs(deck, record, error)
    call check_text_contains('guard_pressure_located', message_of(error), &
      folder//'/block.inp:7: PRESSURE: the pressure is -Infinity')
    call read_deck(folder//'/block.inp', deck, error)
    call clean_record(deck, record)
    deck%mesh%xy(2, 3) = nan
    call check_finite_outputs(deck, record, error)
    call check_text_contains('guard_node_named', message_of(error), &
      'node '//integer_text(deck%mesh%node_id(3))//' has a non-finite coordinate')
  end subroutine test_deck_numbers_guard

  !> |c - e|/|e| without overflow; finite for every finite pair with e /= 0.
  subroutine test_relative_error()
    real(dp) :: tiny_denormal
    tiny_denormal = tiny(1.0_dp)/2.0_dp**52          ! the smallest denormal, 4.9e-324
    call check('relative_error_equal', relative_error(2.5_dp, 2.5_dp) == 0.0_dp)
    call check('relative_error_one_percent', abs(relative_error(1.01_dp, 1.0_dp) - 0.01_dp) < 1.0e-14_dp)
    call check('relative_error_zero_computed', relative_error(0.0_dp, 3.0_dp) == 1.0_dp)
    call check('relative_error_opposite_huge', abs(relative_error(-1.0e308_dp, 1.0e308_dp) - 2.0_dp) < 1.0e-14_dp)
    call check('relative_error_denormal_expected_capped', relative_error(1.0e308_dp, tiny_denormal) == 1.0e300_dp)
    call check('relative_error_denormal_expected_writable', finite_text(table_real(relative_error(-9.8_dp, tiny_denormal))), &
               table_real(relative_error(-9.8_dp, tiny_denormal)))
    call check('relative_error_denormals', abs(relative_error(2.0_dp*tiny_denormal, tiny_denormal) - 1.0_dp) < 1.0e-14_dp)
  end subroutine test_relative_error

  !> EXPECT: one check per card, counted in the tally; 0 and duplicates refused at the card.
  subroutine test_expect_cards()
    type(record_t) :: record
    type(error_t), allocatable :: error
    type(expect_tally_t) :: tally
    character(:), allocatable :: displacement, energy, line
    call run_deck(folder//'/block.inp', folder//'/expect', record, error)
    call check('expect_block_runs', .not. allocated(error), message_of(error))
    if (allocated(error)) return
    displacement = summary_value(record, 'max_displacement_m')
    energy = summary_value(record, 'strain_energy_J')
    call write_deck(folder//'/three.inp', [character(len=80) :: block_deck(1:7), &
      'EXPECT max_displacement_m '//displacement//' RTOL=1e-6', &
      'EXPECT strain_energy_J '//energy//' RTOL=1e-6', &
      'EXPECT external_work_J 1.0 RTOL=1e-6', 'END'])
    call run_deck(folder//'/three.inp', folder//'/expect', record, error, tally)
    call check('expect_three_runs', .not. allocated(error), message_of(error))
    call check('expect_three_counted', tally%count == 3 .and. tally%within == 2)
    call check('expect_three_worst_finite', ieee_is_finite(tally%worst) .and. tally%worst > 1.0e-6_dp)
    line = run_line(record, tally)
    call check_text_contains('expect_run_line_counts_cards', line, '; EXPECT 2/3 within RTOL')
    call check('expect_rel_error_key_finite', finite_text(summary_value(record, 'expect_external_work_J_rel_error')))

    call write_deck(folder//'/zero.inp', [character(len=80) :: block_deck(1:7), &
      'EXPECT strain_energy_J 0', 'END'])
    call run_deck(folder//'/zero.inp', folder//'/expect', record, error)
    call check_text_contains('expect_zero_refused', message_of(error), &
      folder//'/zero.inp:8:24: EXPECT: expected value must be nonzero')
    call write_deck(folder//'/twice.inp', [character(len=80) :: block_deck(1:7), &
      'EXPECT strain_energy_J 1.0', 'EXPECT strain_energy_J 2.0', 'END'])
    call run_deck(folder//'/twice.inp', folder//'/expect', record, error)
    call check_text_contains('expect_twice_refused', message_of(error), &
      folder//'/twice.inp:9:8: EXPECT: key strain_energy_j is already expected on line 8')
  end subroutine test_expect_cards

  !> A deck whose result is not finite today (a modulus of 1e308): an error
  !> naming the deck, nothing in the output root.
  subroutine test_non_finite_run()
    type(record_t) :: record
    type(error_t), allocatable :: error
    character(:), allocatable :: root
    root = folder//'/nonfinite'
    call write_deck(folder//'/huge.inp', [character(len=80) :: block_deck(1:3), &
      'MATERIAL steel ELASTIC E=1e308 NU=0.3', block_deck(5:8)])
    call run_deck(folder//'/huge.inp', root, record, error)
    call check('non_finite_run_refused', allocated(error))
    call check_text_contains('non_finite_run_names_deck', message_of(error), folder//'/huge.inp:')
    call check('non_finite_run_no_output', .not. path_exists(root), root//' exists')
  end subroutine test_non_finite_run

  !> Writers return what failed (an error naming the file); a good write returns none.
  subroutine test_writers()
    type(deck_t) :: deck
    type(record_t) :: record
    type(error_t), allocatable :: error
    call read_deck(folder//'/block.inp', deck, error)
    if (allocated(error)) return
    call clean_record(deck, record)
    call write_summary(folder//'/summary.txt', record, error)
    call check('writer_summary_ok', .not. allocated(error), message_of(error))
    call write_history(folder//'/no/such/folder/history.csv', record, error)
    call check_text_contains('writer_missing_folder', message_of(error), 'cannot create the file')
    call write_listing(folder//'/no/such/folder/listing.txt', 'block', deck, 'none', record, error)
    call check_text_contains('writer_listing_missing_folder', message_of(error), 'cannot create the file')
    call write_results_h5(folder//'/no/such/folder/results.h5', 'block', deck, record, error)
    call check('writer_h5_missing_folder', allocated(error), 'no message')
    call write_results_h5(folder//'/results.h5', 'block', deck, record, error)
    call check('writer_h5_ok', .not. allocated(error), message_of(error))
    call write_results_h5(folder//'/results.h5', 'block', deck, record, error)      ! HDF5 opened and closed again
    call check('writer_h5_twice_ok', .not. allocated(error), message_of(error))
    if (path_exists('/dev/full')) then
      ! /dev/full takes no byte: stdio reports it (the Fortran runtime would not).
      call write_summary('/dev/full', record, error)
      call check_text_contains('writer_dev_full_summary', message_of(error), 'writing failed')
      call check_text_contains('writer_dev_full_names_file', message_of(error), '/dev/full: ')
      call write_history('/dev/full', record, error)
      call check_text_contains('writer_dev_full_history', message_of(error), 'writing failed')
    end if
  end subroutine test_writers

  subroutine test_output_root()
    type(error_t), allocatable :: error
    integer :: unit
    call prepare_output_root('', error)
    call check_text_contains('root_empty_refused', message_of(error), 'the output folder name is empty')
    open(newunit=unit, file=folder//'/plain', status='replace', action='write')
    write(unit, '(a)') 'plain'
    close(unit)
    call prepare_output_root(folder//'/plain/out', error)
    call check_text_contains('root_through_file_refused', message_of(error), folder//'/plain is not a folder')
    if (directory_exists('/proc/self')) then
      call prepare_output_root('/proc/visco2d_test_output_guards', error)
      call check_text_contains('root_uncreatable_refused', message_of(error), 'cannot be created')
    end if
    call prepare_output_root(folder//'/fresh/nested/out', error)
    call check('root_fresh_accepted', .not. allocated(error), message_of(error))
    call check('root_fresh_not_created', .not. path_exists(folder//'/fresh'))
    call prepare_output_root(folder, error)
    call check('root_existing_accepted', .not. allocated(error), message_of(error))
    call check('root_existing_no_probe_left', .not. path_exists(folder//'/.visco2d-probe.'//integer_text(process_id())))
  end subroutine test_output_root

  !> Stale folders of a dead process go (an old folder comes back if its case
  !> folder is missing); a live process's folders and names that are not ours stay.
  subroutine test_stale_folders()
    character(:), allocatable :: root, dead_text
    integer :: dead, unit, status
    type(case_lock_t) :: lock, second
    type(error_t), allocatable :: error
    root = folder//'/stale'
    if (make_directory(root) /= 0) return
    ! A process that has ended: a shell that prints its pid and exits.
    call execute_command_line('sh -c ''echo $$'' > '//folder//'/dead.pid', wait=.true., exitstat=status, cmdstat=unit)
    open(newunit=unit, file=folder//'/dead.pid', status='old', action='read')
    read(unit, *) dead
    close(unit)
    call check('stale_pid_is_dead', .not. process_alive(dead), 'process '//integer_text(dead)//' is alive')
    call check('stale_own_pid_alive', process_alive(process_id()))
    call check('stale_pid_zero_never_alive', .not. process_alive(0) .and. .not. process_alive(-1))
    dead_text = integer_text(dead)
    call make_one(root, '.a.partial.'//dead_text)
    call make_one(root, '.b.partial.1')
    call make_one(root, '.c.partial.'//integer_text(process_id()))
    call make_one(root, '.d.old.'//dead_text)
    call make_one(root, '.e.old.'//dead_text)
    call make_one(root, 'e')
    call make_one(root, '.f.partial.abc')
    call make_one(root, '.h*[x].partial.'//dead_text)
    ! Content to remove with the dead folder: a nested folder, a hidden file, and
    ! a link to a folder outside, which must be removed as a link (never followed).
    call make_one(root, '.a.partial.'//dead_text//'/nested/deeper')
    call make_one(folder, 'outside')
    open(newunit=unit, file=folder//'/outside/keep.txt', status='replace', action='write')
    close(unit)
    open(newunit=unit, file=root//'/.a.partial.'//dead_text//'/nested/.hidden', status='replace', action='write')
    close(unit)
    call execute_command_line('ln -s ../../outside '//root//'/.a.partial.'//dead_text//'/link', &
                              wait=.true., exitstat=status, cmdstat=unit)
    open(newunit=unit, file=root//'/.d.old.'//dead_text//'/summary.txt', status='replace', action='write')
    write(unit, '(a)') 'previous'
    close(unit)
    open(newunit=unit, file=root//'/.g.partial.'//dead_text, status='replace', action='write')   ! a file
    close(unit)
    call remove_stale_folders(root)
    call check('stale_dead_partial_removed', .not. path_exists(root//'/.a.partial.'//dead_text))
    call check('stale_link_not_followed', path_exists(folder//'/outside/keep.txt'))
    call check('stale_pattern_characters_removed', .not. path_exists(root//'/.h*[x].partial.'//dead_text))
    call check('stale_live_partial_kept', directory_exists(root//'/.b.partial.1'))
    call check('stale_own_partial_kept', directory_exists(root//'/.c.partial.'//integer_text(process_id())))
    call check('stale_old_put_back', path_exists(root//'/d/summary.txt') .and. &
               .not. path_exists(root//'/.d.old.'//dead_text))
    call check('stale_old_removed_beside_case', .not. path_exists(root//'/.e.old.'//dead_text) .and. &
               directory_exists(root//'/e'))
    call check('stale_not_a_pid_kept', directory_exists(root//'/.f.partial.abc'))
    call check('stale_file_kept', path_exists(root//'/.g.partial.'//dead_text))
    ! Names with a host: this host's dead run goes, another host's stays; a folder
    ! whose case lock is held stays whatever its pid; a held lock refuses a second one.
    call make_one(root, '.i.partial.'//host_name()//'.'//dead_text)
    call make_one(root, '.j.partial.node17.cluster.'//dead_text)
    call make_one(root, '.k.partial.'//dead_text)
    call lock_case(root, 'k', lock, error)
    call check('lock_taken', .not. allocated(error) .and. path_exists(root//'/.k.lock'), message_of(error))
    call lock_case(root, 'k', second, error)
    call check('lock_second_refused', allocated(error), 'a second lock of case k was granted')
    if (allocated(error)) call check_text_contains('lock_second_names_holder', message_of(error), &
      'by another run (process '//integer_text(process_id())//' on host '//host_name()//', which holds '//root//'/.k.lock)')
    if (allocated(error)) deallocate(error)
    call remove_stale_folders(root)
    call check('stale_own_host_dead_removed', .not. path_exists(root//'/.i.partial.'//host_name()//'.'//dead_text))
    call check('stale_other_host_kept', directory_exists(root//'/.j.partial.node17.cluster.'//dead_text))
    call check('stale_locked_case_kept', directory_exists(root//'/.k.partial.'//dead_text))
    call unlock_case(lock)
    call check('lock_released_file_removed', .not. path_exists(root//'/.k.lock'))
    call remove_stale_folders(root)
    call check('stale_unlocked_case_removed', .not. path_exists(root//'/.k.partial.'//dead_text))
    ! The root written with a trailing slash names the same folders.
    call make_one(root, '.z.old.'//dead_text)
    call remove_stale_folders(root//'/')
    call check('stale_trailing_slash_put_back', directory_exists(root//'/z') .and. &
               .not. path_exists(root//'/.z.old.'//dead_text))
  end subroutine test_stale_folders

  subroutine make_one(root, name)
    character(*), intent(in) :: root, name
    if (make_directory(root//'/'//name) /= 0) print '(a)', '  cannot create '//name
  end subroutine make_one

  !> record_warn: located like a deck warning, counted, listed in listing.txt.
  subroutine test_run_warnings()
    type(deck_t) :: deck
    type(record_t) :: record
    type(error_t), allocatable :: error
    character(:), allocatable :: listing(:)
    logical :: found
    call read_deck(folder//'/block.inp', deck, error)
    if (allocated(error)) return
    call clean_record(deck, record)
    call check('run_warnings_none', run_warning_count(record) == 0)
    call record_warn(record, 'the energy balance error is 7 % of the input', file='d.inp', line=12, card='TIME')
    call record_warn(record, 'no location')
    call check('run_warnings_counted', run_warning_count(record) == 2)
    call check('run_warning_located', record%warnings(1)%text == &
               'd.inp:12: TIME: the energy balance error is 7 % of the input', record%warnings(1)%text)
    call check('run_warning_plain', record%warnings(2)%text == 'no location', record%warnings(2)%text)
    call write_listing(folder//'/listing.txt', 'block', deck, 'none', record, error)
    call check('run_warnings_listing_written', .not. allocated(error), message_of(error))
    call read_lines(folder//'/listing.txt', listing, found)
    call check('run_warnings_in_listing', &
               any(listing == '   d.inp:12: TIME: the energy balance error is 7 % of the input'))
  end subroutine test_run_warnings
end program test_output_guards
