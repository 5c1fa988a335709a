!> Guards of the card reader (issue 13, "never a silent wrong answer"): each
!> defect found by fuzzing and by hand has its regression deck here.
!> - a card longer than 4096 columns is read whole (its tail was lost);
!> - a PRONY card first in the deck is an error, not a read of cards(0);
!> - summary keys are never cut (a long PROBE name made EXPECT count 1 of 3);
!> - every number is finite, normal and within its physical range, refused
!>   at its field's column otherwise (visco2d_ranges);
!> - DT and TEND whose step count overflows, and DT longer than its stage;
!> - numbers in messages keep their E (1.0000E-300, not 1.0000-300);
!> - a directory, a binary file, a missing file and an empty name are named;
!> - missing and misplaced cards are located; near-miss keywords suggested.
program test_input_guards
  use visco2d_kinds, only: dp
  use visco2d_error, only: error_t, error_text
  use visco2d_deck, only: deck_t, read_deck, total_steps
  use visco2d_driver, only: run_deck
  use visco2d_expect, only: summary_value
  use visco2d_record, only: record_t
  use visco2d_cards, only: parse_real, max_line_length
  use visco2d_curve, only: curve_t, curve_value
  use visco2d_strings, only: integer_text, message_real, table_real, es_field, short_real, compact_real
  use visco2d_testing, only: check, check_close, check_text_contains, test_summary, write_deck, message_of, &
                             read_lines
  use visco2d_test_decks, only: deck_line_length, square, creep, impact_in_gravity, try_read_deck
  implicit none

  character(*), parameter :: folder = 'build/test_decks/guards'
  character(*), parameter :: out_root = 'build/test_decks/guards_out'
  character(len=deck_line_length), allocatable :: lines(:)

  call execute_command_line('rm -rf '//folder//' '//out_root)
  call execute_command_line('mkdir -p '//folder//' '//out_root)

  call long_lines()
  call prony_first()
  call long_summary_keys()
  call number_syntax()
  call material_ranges()
  call scene_ranges()
  call load_ranges()
  call time_ranges()
  call expect_ranges()
  call message_numbers()
  call deck_files()
  call card_structure()
  call fuzz_findings()
  call curve_lookup()

  call execute_command_line('rm -rf '//out_root)
  deallocate(lines)
  call test_summary('test_input_guards')

contains

  ! ------------------------------------------------------------------ cases

  !> Issue 13: `FIX 2 Z` + 5000 blanks + `UZ=-1e-4` lost its UZ (the reader's
  !> buffer was 4096 characters and only a line filling it was refused).
  subroutine long_lines()
    type(deck_t) :: deck
    type(error_t), allocatable :: error
    character(:), allocatable :: path
    integer :: unit, k
    path = folder//'/long_line.inp'
    lines = square()
    open(newunit=unit, file=path, status='replace', action='write')
    write(unit, '(a)') (trim(lines(k)), k = 1, 10)
    write(unit, '(a)') 'FIX 2 Z'//repeat(' ', 5000)//'UZ=-1e-4'
    write(unit, '(a)') 'END'
    close(unit)
    call read_deck(path, deck, error)
    call check('long_line_reads', .not. allocated(error), message_of(error))
    if (.not. allocated(error)) then
      call check('long_line_two_fixes', size(deck%loads%fixes) == 2)
      if (size(deck%loads%fixes) == 2) call check('long_line_tail_kept', deck%loads%fixes(2)%value(2) == -1.0e-4_dp, &
        'the UZ= after column 5000 was lost: u_z = '//message_real(deck%loads%fixes(2)%value(2)))
    end if

    ! A line longer than any deck needs is an error at its line, never a cut.
    path = folder//'/too_long_line.inp'
    open(newunit=unit, file=path, status='replace', action='write')
    write(unit, '(a)') 'TITLE t'
    write(unit, '(a)') 'ANALYSIS STATIC '//repeat(' ', max_line_length)//'X'
    write(unit, '(a)') 'END'
    close(unit)
    call expect_error_at('too_long_line', path, 2, max_line_length + 1, '', 'line longer than')

    ! Many fields (the reader used to stop at 512): a curve of 400 points.
    block
      character(:), allocatable :: curve
      integer :: k
      curve = 'CURVE load'
      do k = 0, 399
        curve = curve//' '//integer_text(k)//'e-3 '//integer_text(mod(k, 7))
      end do
      path = folder//'/many_fields.inp'
      lines = creep()
      open(newunit=unit, file=path, status='replace', action='write')
      write(unit, '(a)') (trim(lines(k)), k = 1, 8)
      write(unit, '(a)') curve
      write(unit, '(a)') (trim(lines(k)), k = 10, 11)
      close(unit)
      call read_deck(path, deck, error)
      call check('many_fields_reads', .not. allocated(error), message_of(error))
      if (.not. allocated(error)) then
        call check('many_fields_points', size(deck%loads%curves(1)%time) == 400)
        call check('many_fields_last_point', deck%loads%curves(1)%time(400) == 0.399_dp .and. &
                   deck%loads%curves(1)%value(400) == real(mod(399, 7), dp))
      end if
    end block
  end subroutine long_lines

  !> Issue 13: a PRONY card first read cards%cards(0) (`.or.` does not short-circuit).
  subroutine prony_first()
    lines = creep()
    call expect_read_error('prony_first_card', [lines(5), lines(1:4), lines(6:)], &
                           1, 1, 'PRONY', 'PRONY must follow its MATERIAL card')
    lines = creep()
    call expect_read_error('prony_second_card', [lines(1), lines(5), lines(2:4), lines(6:)], &
                           2, 1, 'PRONY', 'PRONY must follow its MATERIAL card')
  end subroutine prony_first

  !> Issue 13: keys were cut at 48 characters, so the three EXPECT keys of a
  !> probe with a long name became one (EXPECT 1/1 when 3 were given, one failing).
  subroutine long_summary_keys()
    type(record_t) :: record
    type(error_t), allocatable :: error
    character(*), parameter :: name = 'a_probe_with_a_long_name'   ! 24 characters, the most allowed
    character(:), allocatable :: path, key
    integer :: i, within, checks
    path = folder//'/long_keys.inp'
    lines = square()
    lines = [character(len=deck_line_length) :: lines(1:11), 'FORCE 3 FZ=-1e3', 'PROBE '//name//' NODE=3', &
      'EXPECT probe_'//name//'_r_m 1.0 RTOL=1e-12', &      ! node 3 is at r = 1: within
      'EXPECT probe_'//name//'_z_m 1.0 RTOL=1e-12', &      ! and z = 1: within
      'EXPECT probe_'//name//'_uz_m 1.0 RTOL=1e-12', &     ! u_z is ~1e-8 m, not 1 m: outside
      'END']
    call write_deck(path, lines)
    call run_deck(path, out_root, record, error)
    call check('long_keys_runs', .not. allocated(error), message_of(error))
    if (allocated(error)) return
    checks = 0
    within = 0
    do i = 1, record%nsummary
      key = record%summary(i)%key
      if (index(key, 'expect_') == 1 .and. index(key, '_within_rtol') > 0) then
        checks = checks + 1
        if (record%summary(i)%value == 'yes') within = within + 1
      end if
    end do
    call check('long_keys_three_checks', checks == 3, integer_text(checks)//' EXPECT checks recorded, 3 given')
    call check('long_keys_two_within', within == 2, integer_text(within)//' within RTOL, 2 expected')
    key = 'expect_probe_'//name//'_uz_m_within_rtol'
    call check('long_keys_whole_key', summary_value(record, key) == 'no', &
               key//' ('//integer_text(len(key))//' characters) = "'//summary_value(record, key)//'"')
  end subroutine long_summary_keys

  !> parse_real: finite, normal doubles only.
  subroutine number_syntax()
    call expect_number('1.5e3', .true., 1.5e3_dp)
    call expect_number('-2.5D-2', .true., -2.5e-2_dp)
    call expect_number('0', .true., 0.0_dp)
    call expect_number('0.0e-999', .true., 0.0_dp)   ! zero written with any exponent is zero
    call expect_number('1e308', .true., 1.0e308_dp)
    call expect_number('2.3e-308', .true., 2.3e-308_dp)
    call expect_number('1e999', .false., 0.0_dp, 'finite')
    call expect_number('-1e309', .false., 0.0_dp, 'finite')
    call expect_number('1e-999', .false., 0.0_dp, 'too small')
    call expect_number('4.9e-324', .false., 0.0_dp, 'too small')
    call expect_number('1e-310', .false., 0.0_dp, 'too small')
    call expect_number('NaN', .false., 0.0_dp, 'finite')
    call expect_number('-Inf', .false., 0.0_dp, 'finite')
    call expect_number('Infinity', .false., 0.0_dp, 'finite')
    call expect_number('1.2.3', .false., 0.0_dp, 'a number')
    call expect_number('e5', .false., 0.0_dp, 'a number')

    lines = square()
    lines(4) = 'MATERIAL steel ELASTIC E=1e999 NU=0.3'
    call expect_read_error('e_overflow', lines, 4, 24, 'MATERIAL', 'E must be a finite number')
    lines(4) = 'MATERIAL steel ELASTIC E=NaN NU=0.3'
    call expect_read_error('e_nan', lines, 4, 24, 'MATERIAL', 'E must be a finite number, got "NaN"')
    lines(4) = 'MATERIAL steel ELASTIC E=4.9e-324 NU=0.3'
    call expect_read_error('e_subnormal', lines, 4, 24, 'MATERIAL', 'E is too small to be a normal double')
    lines = square()
    lines = [character(len=deck_line_length) :: lines(1:11), 'PROBE p NODE=1234567890', lines(12)]
    call expect_read_error('probe_node_ten_digits', lines, 12, 9, 'PROBE', &
                           'NODE must be an integer of at most 9 digits, got "1234567890"')
  end subroutine number_syntax

  !> Moduli, density, Poisson's ratio (K/G), Prony terms.
  subroutine material_ranges()
    lines = square()
    lines(4) = 'MATERIAL steel ELASTIC E=1e308 NU=0.3'
    call expect_read_error('e_huge', lines, 4, 24, 'MATERIAL', 'E must be in [0.001, 1e14] Pa, got "1e308"')
    lines(4) = 'MATERIAL steel ELASTIC E=1e-300 NU=0.3'
    call expect_read_error('e_tiny', lines, 4, 24, 'MATERIAL', 'E must be in [0.001, 1e14] Pa, got "1e-300"')
    lines(4) = 'MATERIAL steel ELASTIC G=1e9 K=2e15'
    call expect_read_error('k_huge', lines, 4, 30, 'MATERIAL', 'K must be in [0.001, 1e14] Pa')
    lines(4) = 'MATERIAL steel ELASTIC E=200e9 NU=0.3 RHO=1e6'
    call expect_read_error('rho_huge', lines, 4, 39, 'MATERIAL', 'RHO must be 0 or in [0.001, 1e5] kg/m^3, got "1e6"')
    lines(4) = 'MATERIAL steel ELASTIC E=200e9 NU=0.3 RHO=1e-30'
    call expect_read_error('rho_tiny', lines, 4, 39, 'MATERIAL', 'RHO must be 0 or in [0.001, 1e5] kg/m^3')
    lines(4) = 'MATERIAL steel ELASTIC E=200e9 NU=0.49999999'
    call expect_read_error('nu_ill_conditioned', lines, 4, 32, 'MATERIAL', 'K/G = 5.0000E+07')
    lines(4) = 'MATERIAL steel ELASTIC G=1e9 K=1e-3'
    call expect_read_error('g_over_k_ill_conditioned', lines, 4, 30, 'MATERIAL', 'is outside [1e-6, 1e6]')
    ! nu = 0.4999 (K/G = 5000, rubber-like) is accepted: the bound is far from real materials.
    lines(4) = 'MATERIAL steel ELASTIC E=200e9 NU=0.4999'
    call expect_valid('nu_rubber_accepted', lines)

    lines = creep()
    lines(5) = 'PRONY G=1e15 BETA=10'
    call expect_read_error('prony_g_huge', lines, 5, 7, 'PRONY', 'G must be in [0.001, 1e14] Pa, got "1e15"')
    lines(5) = 'PRONY G=1e6 BETA=1e13'
    call expect_read_error('prony_beta_huge', lines, 5, 13, 'PRONY', 'BETA must be 0 or in [1e-12, 1e12] 1/s')
    lines(5) = 'PRONY G=1e6 BETA=1e-300'
    call expect_read_error('prony_beta_tiny', lines, 5, 13, 'PRONY', 'BETA must be 0 or in [1e-12, 1e12] 1/s')
    lines = creep()
    call expect_read_error('prony_duplicated', [lines(1:5), lines(5:)], 6, 13, 'PRONY', &
                           'already has a term with BETA = 10.0 1/s (line 5)')
    ! The instantaneous K/G of a viscoelastic material: G(0) = 1 Pa against K = 2 MPa.
    lines = creep()
    lines(5) = 'PRONY G=1 BETA=10'
    call expect_read_error('prony_ill_conditioned', lines, 4, 29, 'MATERIAL', 'K/G = 2.0000E+06')
  end subroutine material_ranges

  !> Speeds, accelerations, gravity, drop height, plate, probes, FIELDS.
  subroutine scene_ranges()
    lines = impact_in_gravity()
    lines(6) = 'INITIAL VZ=-1e5'
    call expect_read_error('vz_huge', lines, 6, 9, 'INITIAL', 'VZ must be 0 or of magnitude in [1e-9, 1e4] m/s')
    lines(6) = 'INITIAL VZ=-1e-300'
    call expect_read_error('vz_tiny', lines, 6, 9, 'INITIAL', 'VZ must be 0 or of magnitude in [1e-9, 1e4] m/s')
    lines(6) = 'INITIAL VZ=-1 AZ=1e9'
    call expect_read_error('az_huge', lines, 6, 15, 'INITIAL', 'AZ must be in [-1e8, 1e8] m/s^2')
    lines = impact_in_gravity()
    lines(8) = 'GRAVITY G=1e7'
    call expect_read_error('gravity_huge', lines, 8, 9, 'GRAVITY', 'G must be 0 or in [1e-6, 1e6] m/s^2')
    lines = impact_in_gravity()
    lines(6) = 'DROP HEIGHT=1e4'
    call expect_read_error('drop_huge', lines, 6, 6, 'DROP', 'HEIGHT must be 0 or in [1e-9, 1000] m')
    lines(6) = 'DROP HEIGHT=1e-300'
    call expect_read_error('drop_tiny', lines, 6, 6, 'DROP', 'HEIGHT must be 0 or in [1e-9, 1000] m')
    lines(6) = 'DROP HEIGHT=1000'
    lines(8) = 'GRAVITY G=1e6'
    call expect_read_error('drop_speed_huge', lines, 6, 6, 'DROP', &
                           'gives VZ = -44721.359549995796 m/s; the speed must be 0 or of magnitude in [1e-9, 1e4] m/s')
    lines = impact_in_gravity()
    lines(7) = 'PLATE Z=-1e5'
    call expect_read_error('plate_far', lines, 7, 7, 'PLATE', 'Z must be in [-1e4, 1e4] m, got "-1e5"')
    lines = impact_in_gravity()
    lines(10) = 'OUTPUT FIELDS=1e10'
    call expect_read_error('fields_time_huge', lines, 10, 8, 'OUTPUT', 'FIELDS times must be in [0, 1e9] s')
    lines = square()
    lines = [character(len=deck_line_length) :: lines(1:11), 'PROBE p R=1e300 Z=0', lines(12)]
    call expect_read_error('probe_far', lines, 12, 9, 'PROBE', 'R must be in [-1e4, 1e4] m')
  end subroutine scene_ranges

  !> Pressures, forces, prescribed displacements, curves and their products.
  subroutine load_ranges()
    lines = creep()
    lines(8) = 'PRESSURE TOP P=1e308 CURVE=load'
    call expect_read_error('pressure_huge', lines, 8, 14, 'PRESSURE', 'P must be in [-1e12, 1e12] Pa, got "1e308"')
    lines = creep()
    lines(9) = 'CURVE load 0 0 1 1e7'
    call expect_read_error('curve_value_huge', lines, 9, 18, 'CURVE', 'value of point 2 must be in [-1e6, 1e6]')
    lines(9) = 'CURVE load 0 0 1e10 1'
    call expect_read_error('curve_time_huge', lines, 9, 16, 'CURVE', 'time of point 2 must be in [0, 1e9] s')
    lines(9) = 'CURVE load -1 0 1 1'
    call expect_read_error('curve_time_negative', lines, 9, 12, 'CURVE', 'time of point 1 must be in [0, 1e9] s')
    lines = creep()
    lines(8) = 'PRESSURE TOP P=1e9 CURVE=load'
    lines(9) = 'CURVE load 0 0 1 1e6'
    call expect_read_error('pressure_times_curve_huge', lines, 8, 20, 'PRESSURE', &
                           'P times curve LOAD (line 9) reaches 1.0000E+15: it must stay in [-1e12, 1e12] Pa')
    lines = square()
    lines = [character(len=deck_line_length) :: lines(1:11), 'FORCE 3 FZ=-1e13', lines(12)]
    call expect_read_error('force_huge', lines, 12, 9, 'FORCE', 'FZ must be in [-1e12, 1e12] N')
    lines = square()
    lines(11) = 'FIX 2 Z UZ=1e5'
    call expect_read_error('fix_uz_huge', lines, 11, 9, 'FIX', 'UZ must be in [-1e4, 1e4] m')
  end subroutine load_ranges

  !> DT, TEND and the step count.
  subroutine time_ranges()
    type(deck_t) :: deck
    type(error_t), allocatable :: error
    lines = creep()
    lines(10) = 'TIME DT=1e308 TEND=1'
    call expect_read_error('dt_huge', lines, 10, 6, 'TIME', 'DT must be in [1e-12, 1e9] s, got "1e308"')
    lines(10) = 'TIME DT=10 TEND=1'
    call expect_read_error('dt_longer_than_stage', lines, 10, 6, 'TIME', &
                           'DT = 10.0 s is longer than the stage it steps through (0.0 s to TEND = 1.0 s, 1.0 s)')
    lines(10) = 'TIME DT=4.9e-324 TEND=1'
    call expect_read_error('dt_subnormal', lines, 10, 6, 'TIME', 'DT is too small to be a normal double')
    lines(10) = 'TIME DT=1e-13 TEND=1'
    call expect_read_error('dt_tiny', lines, 10, 6, 'TIME', 'DT must be in [1e-12, 1e9] s')
    lines(10) = 'TIME DT=1e-12 TEND=1e9'
    call expect_read_error('steps_overflow', lines, 10, 6, 'TIME', 'would take more than 10000000 steps')
    lines(10) = 'TIME DT=1 TEND=1e10'
    call expect_read_error('tend_huge', lines, 10, 11, 'TIME', 'TEND must be in [0, 1e9] s')
    ! Stages that add up past the limit: the sum is taken in 64 bits.
    lines = creep()
    lines = [character(len=deck_line_length) :: lines(1:9), 'TIME DT=1e-6 TEND=6', 'TIME DT=1e-6 TEND=12', lines(11)]
    call expect_read_error('stages_add_up', lines, 11, 6, 'TIME', 'the TIME stages add up to 12000000 steps')
    ! A valid multi-stage axis: whole steps, total as the sum.
    lines = creep()
    lines = [character(len=deck_line_length) :: lines(1:10), 'TIME DT=0.5 TEND=3', lines(11)]
    call write_deck(folder//'/two_stages.inp', lines)
    call read_deck(folder//'/two_stages.inp', deck, error)
    call check('two_stages_read', .not. allocated(error), message_of(error))
    if (.not. allocated(error)) call check('two_stages_total', total_steps(deck) == 14, &
                                           'total_steps = '//integer_text(total_steps(deck))//', expected 10 + 4')
  end subroutine time_ranges

  !> EXPECT: a nonzero finite value, a tolerance, one card per key.
  subroutine expect_ranges()
    lines = square()
    lines = [character(len=deck_line_length) :: lines(1:11), 'EXPECT max_displacement_m 0', lines(12)]
    call expect_read_error('expect_zero', lines, 12, 27, 'EXPECT', &
                           'expected value must be nonzero, of magnitude in [1e-200, 1e200], got "0"')
    lines(12) = 'EXPECT max_displacement_m 1e300'
    call expect_read_error('expect_huge', lines, 12, 27, 'EXPECT', 'expected value must be nonzero')
    lines(12) = 'EXPECT max_displacement_m 1e-3 RTOL=1e-30'
    call expect_read_error('expect_rtol_tiny', lines, 12, 32, 'EXPECT', 'RTOL must be in [1e-15, 1000]')
    lines(12) = 'EXPECT max_displacement_m 1e-3 RTOL=0'
    call expect_read_error('expect_rtol_zero', lines, 12, 32, 'EXPECT', 'RTOL must be in [1e-15, 1000]')
    lines = square()
    lines = [character(len=deck_line_length) :: lines(1:11), 'EXPECT max_displacement_m 1e-3', &
             'EXPECT MAX_displacement_m 2e-3', lines(12)]
    call expect_read_error('expect_twice', lines, 13, 8, 'EXPECT', 'key max_displacement_m is already expected on line 12')
  end subroutine expect_ranges

  !> Numbers in messages: the E of a three-digit exponent is kept.
  subroutine message_numbers()
    call check_text('rtoa_small', message_real(1.0e-300_dp), '1.0000E-300')
    call check_text('rtoa_large', message_real(-1.5e300_dp), '-1.5000E+300')
    call check_text('rtoa_usual', message_real(1.811e7_dp), '1.8110E+07')       ! unchanged for usual exponents
    call check_text('rtoa_rounds_up', message_real(9.99999e99_dp), '1.0000E+100')
    call check_text('gtoa_usual', table_real(1.811e7_dp), '1.811000000E+007')  ! the summary format, unchanged
    call check_text('short_real_huge', short_real(1.0e308_dp), '1.0E+308')
    call check_text('short_real_subnormal', short_real(tiny(1.0_dp)*1.0e-15_dp),&
      '2.5E-323')   ! the subnormal nearest 2.2e-323 is 2.47e-323
    call check_text('short_real_small', short_real(1.0e-7_dp), '1.0E-07')
    call check_text('short_real_plain', short_real(0.002_dp), '0.002')
    call check_text('short_real_integer', short_real(18.11e6_dp), '18110000.0')
    call check_text('short_real_shortest', short_real(0.1_dp + 0.2_dp), '0.30000000000000004')
    call check_text('es_field_usual', es_field(1.811e7_dp, 16, 8), '  1.81100000E+07')
    call check_text('es_field_negative', es_field(-2.5e-3_dp, 16, 8), ' -2.50000000E-03')
    call check_text('es_field_three_digit_exponent', es_field(1.0e-300_dp, 16, 8), '  1.0000000E-300')
    call check_text('es_field_huge_negative', es_field(-1.5e300_dp, 16, 8), ' -1.5000000E+300')
    call check_text('compact_real_range', compact_real(1.0e14_dp)//' '//compact_real(1.0e-3_dp)//' '// &
                    compact_real(-1.0e4_dp)//' '//compact_real(1.0e-12_dp), '1e14 0.001 -1e4 1e-12')
    block
      real(dp) :: back
      character(len=40) :: text
      integer :: ios, k
      real(dp), parameter :: values(6) = [1.0e-300_dp, 0.7_dp, 123456789.123_dp, -2.5e-5_dp, 1.0e15_dp, 6.02e23_dp]
      do k = 1, size(values)
        text = short_real(values(k))
        read(text, *, iostat=ios) back
        call check('short_real_round_trip_'//integer_text(k), ios == 0 .and. back == values(k), short_real(values(k)))
      end do
    end block
  end subroutine message_numbers

  !> A directory, a binary file, a lone carriage return, a missing file, an empty name.
  subroutine deck_files()
    type(deck_t) :: deck
    type(error_t), allocatable :: error
    character(:), allocatable :: path
    integer :: unit, k
    call read_deck(folder, deck, error)
    call check('directory_error', allocated(error))
    if (allocated(error)) call check_text_contains('directory_message', error_text(error), &
                                                   folder//': cannot read deck: this is a directory')

    path = folder//'/binary.inp'
    open(newunit=unit, file=path, status='replace', access='stream', form='unformatted', action='write')
    write(unit) 'TITLE t'//achar(10)//'ANAL'//achar(0)//achar(255)//'YSIS STATIC'//achar(10)//'END'//achar(10)
    close(unit)
    call expect_error_at('binary_file', path, 2, 5, '', 'a control byte (0) where text was expected')

    path = folder//'/old_mac_line_ends.inp'
    open(newunit=unit, file=path, status='replace', access='stream', form='unformatted', action='write')
    write(unit) 'TITLE t'//achar(13)//'ANALYSIS STATIC'//achar(13)//'END'//achar(10)
    close(unit)
    ! A lone carriage return ends a line, as CR LF does (the deck below then lacks a MATERIAL on its line 3).
    call expect_error_at('lone_carriage_return', path, 3, 1, 'END', 'missing MATERIAL card')

    ! CR LF line ends are read as usual.
    path = folder//'/crlf.inp'
    lines = square()
    open(newunit=unit, file=path, status='replace', access='stream', form='unformatted', action='write')
    write(unit) (trim(lines(k))//achar(13)//achar(10), k = 1, size(lines))
    close(unit)
    call read_deck(path, deck, error)
    call check('crlf_reads', .not. allocated(error), message_of(error))

    ! A UTF-8 byte-order mark before the first card is skipped.
    path = folder//'/byte_order_mark.inp'
    open(newunit=unit, file=path, status='replace', access='stream', form='unformatted', action='write')
    write(unit) achar(239)//achar(187)//achar(191)
    write(unit) (trim(lines(k))//achar(10), k = 1, size(lines))
    close(unit)
    call read_deck(path, deck, error)
    call check('byte_order_mark_reads', .not. allocated(error), message_of(error))
    if (.not. allocated(error)) call check('byte_order_mark_title', deck%title == 'unit square', '"'//deck%title//'"')

    call read_deck(folder//'/no_such_deck.inp', deck, error)
    call check('missing_file_error', allocated(error))
    if (allocated(error)) call check_text_contains('missing_file_message', error_text(error), &
                                                   folder//'/no_such_deck.inp: cannot open deck: file does not exist')
    call read_deck('', deck, error)
    call check('empty_name_error', allocated(error))
    if (allocated(error)) call check_text_contains('empty_name_message', error_text(error), 'the file name is empty')
  end subroutine deck_files

  !> Near-miss keywords, a card after END, the location of missing cards.
  subroutine card_structure()
    lines = square()
    lines(4) = 'MATERAL steel ELASTIC E=200e9 NU=0.3'
    call expect_read_error('near_miss_keyword', lines, 4, 1, 'MATERAL', 'unknown card "MATERAL" (did you mean MATERIAL?)')
    lines = square()
    lines(2) = 'ANALYSSI STATIC'
    call expect_read_error('near_miss_swapped_letters', lines, 2, 1, 'ANALYSSI', '(did you mean ANALYSIS?)')
    lines = square()
    lines(2) = 'XYZZY STATIC'
    call expect_read_error('far_keyword', lines, 2, 1, 'XYZZY', 'unknown card "XYZZY" (known:')
    ! END swapped with the FIX above it: the FIX would have been dropped.
    lines = square()
    call expect_read_error('card_after_end', [lines(1:10), lines(12), lines(11)], 12, 1, 'FIX', &
                           'this card comes after END (line 11) and would be ignored')
    ! Free text after END is still allowed (notes).
    block
      character(len=deck_line_length) :: notes(14)
      notes(1:12) = square()
      notes(13:14) = [character(len=deck_line_length) :: 'notes: measured on 3 May', '  1 2 3']
      call expect_valid('notes_after_end', notes)
    end block
    ! A duplicated load line would double the load.
    lines = creep()
    call expect_read_error('pressure_duplicated', [lines(1:8), lines(8:)], 9, 14, 'PRESSURE', &
                           'the same pressure as on line 8 (a duplicated line?)')
    lines = square()
    lines = [character(len=deck_line_length) :: lines(1:11), 'FORCE 3 FZ=-1e3', 'FORCE 3 FZ=-1e3', lines(12)]
    call expect_read_error('force_duplicated', lines, 13, 7, 'FORCE', 'the same force as on line 12')
    ! Two different loads on one set are a sum, as before.
    lines = creep()
    lines = [character(len=deck_line_length) :: lines(1:8), 'PRESSURE TOP P=2e4', lines(9:)]
    call expect_valid('pressure_two_loads', lines)
    lines = square()
    lines(4) = 'MATERIAL steel ELASTIC E=200e9 NU=0.3 RH0=7800'
    call expect_read_error('near_miss_field', lines, 4, 39, 'MATERIAL', 'unknown field RH0, did you mean RHO? (expected:')
    lines = square()
    call expect_read_error('nodes_without_elements', [lines(1:8), lines(10:12)], 5, 1, 'NODE', &
                           'missing elements: NODE cards need ELEMENT cards')
    lines = creep()
    lines(3) = 'GEOMETRY AXISYMETRIC'
    call expect_read_error('geometry_column', lines, 3, 10, 'GEOMETRY', 'geometry must be AXISYMMETRIC or PLANESTRAIN')
  end subroutine card_structure

  !> Decks the mutation fuzzer reduced (issue 13) whose numbers reached an
  !> output as NaN/Infinity or made an unreadable one on the old reader.
  subroutine fuzz_findings()
    character(len=deck_line_length), allocatable :: fuzz(:)
    character(:), allocatable :: text, listing(:)
    integer :: k
    logical :: found, malformed
    fuzz = [character(len=deck_line_length) :: 'ANALYSIS DYNAMIC', &
      'MATERIAL apple ELASTIC E=18.11e6 NU=0.219 RHO=756.85', 'MESH SPHERE R=0.0366 LEVEL=1', 'GRAVITY G=9.8', &
      'TIME DT=1e-5 TEND=2e-3', 'EXPECT az_cm_m_s2 4.9e-324 RTOL=1e-9', 'END']
    call expect_read_error('fuzz_d000017_expect_subnormal', fuzz, 6, 19, 'EXPECT', 'expected value is too small')
    fuzz = [character(len=deck_line_length) :: 'ANALYSIS DYNAMIC', 'MATERIAL golden VISCOELASTIC K=1e-308 RHO=790', &
      'PRONY G=0.099e6 BETA=35.26', 'MESH SPHERE R=0.035 LEVEL=1', 'INITIAL VZ=-0.7 AZ=-9.8', 'TIME DT=1e-5 TEND=8e-3', &
      'PLATE Z=0 STICK', 'END']
    call expect_read_error('fuzz_d000373_bulk_subnormal', fuzz, 2, 30, 'MATERIAL', 'K is too small')
    fuzz = [character(len=deck_line_length) :: 'ANALYSIS QUASISTATIC', &
      'MATERIAL apple VISCOELASTIC K=1.756e6 RHO=790', 'PRONY G=0.099e6 BETA=35.26', &
      'MESH RECT R0=0 R1=0.01 Z0=0 Z1=0.01 NR=2 NZ=2', 'FIX BOTTOM Z', 'TIME DT=1000 TEND=10000', &
      'GRAVITY G=1e300', 'END']
    call expect_read_error('fuzz_d000957_gravity_huge', fuzz, 7, 9, 'GRAVITY', 'G must be 0 or in [1e-6, 1e6] m/s^2')
    fuzz = [character(len=deck_line_length) :: 'ANALYSIS STATIC', &
      'MATERIAL fruit ELASTIC E=18.11e6 NU=0.219 RHO=1e300', 'MESH SPHERE R=0.0366 LEVEL=1', 'FIX TOP Z', 'END']
    call expect_read_error('fuzz_d000521_density_huge', fuzz, 2, 43, 'MATERIAL', 'RHO must be 0 or in')
    fuzz = [character(len=deck_line_length) :: 'ANALYSIS DYNAMIC', 'MATERIAL golden VISCOELASTIC K=1.756e6 RHO=790', &
      'PRONY G=0.099e6 BETA=4.9e-324', 'MESH SPHERE R=0.035 LEVEL=1', 'TIME DT=2e-5 TEND=15e-3', 'END']
    call expect_read_error('fuzz_d000311_rate_subnormal', fuzz, 3, 17, 'PRONY', 'BETA is too small')

    ! A valid deck whose listing printed -1.71107068-200 (ES16.8 drops the E of a three-digit exponent).
    block
      type(record_t) :: record
      type(error_t), allocatable :: error
      fuzz = [character(len=deck_line_length) :: 'ANALYSIS DYNAMIC', &
        'MATERIAL ground ELASTIC E=8.333333333333333e6 NU=0.25 RHO=1000', &
        'MESH RECT R0=0.01 R1=0.0125 Z0=0 Z1=1 NR=1 NZ=400', 'PRESSURE TOP P=1e5', 'TIME DT=5e-6 TEND=0.005', &
        'PROBE d025 R=0.01 Z=0.75', 'END']
      call write_deck(folder//'/fuzz_d000032_listing.inp', fuzz)
      call run_deck(folder//'/fuzz_d000032_listing.inp', out_root, record, error)
      call check('fuzz_d000032_runs', .not. allocated(error), message_of(error))
      if (allocated(error)) return
      text = out_root//'/fuzz_d000032_listing/listing.txt'
      call read_lines(text, listing, found)
      call check('fuzz_d000032_listing_exists', found, text)
      if (.not. found) return
      malformed = .false.
      do k = 1, size(listing)
        malformed = malformed .or. has_bare_exponent(trim(listing(k)))
      end do
      call check('fuzz_d000032_listing_exponents', .not. malformed, 'a number like 1.0-200 (no E) in '//text)
    end block
  end subroutine fuzz_findings

  !> curve_value finds its interval by bisection: the values of a
  !> piecewise-linear curve at and between its points, and outside them.
  subroutine curve_lookup()
    type(curve_t) :: curve
    real(dp), parameter :: t(8) = [-1.0_dp, 0.0_dp, 0.5_dp, 1.0_dp, 2.0_dp, 3.5_dp, 4.0_dp, 10.0_dp]
    real(dp), parameter :: expected(8) = [0.0_dp, 0.0_dp, 1.0_dp, 2.0_dp, 0.5_dp, 2.0_dp, 5.0_dp, 5.0_dp]
    integer :: k
    curve%time = [0.0_dp, 1.0_dp, 3.0_dp, 4.0_dp]
    curve%value = [0.0_dp, 2.0_dp, -1.0_dp, 5.0_dp]
    do k = 1, size(t)
      call check_close('curve_value_at_'//integer_text(k), curve_value(curve, t(k)), expected(k), 0.0_dp, 1.0e-15_dp)
    end do
  end subroutine curve_lookup

  !> True if the text holds a digit, then a sign, then three digits, with no E before the sign.
  pure logical function has_bare_exponent(text)
    character(*), intent(in) :: text
    integer :: i
    has_bare_exponent = .false.
    do i = 2, len(text) - 3
      if (scan(text(i:i), '+-') == 0) cycle
      if (verify(text(i - 1:i - 1), '0123456789') /= 0) cycle
      if (verify(text(i + 1:i + 3), '0123456789') /= 0) cycle
      has_bare_exponent = .true.
      return
    end do
  end function has_bare_exponent

  ! ---------------------------------------------------------------- helpers

  subroutine expect_number(text, ok_expected, value_expected, reason_fragment)
    character(*), intent(in) :: text
    logical, intent(in) :: ok_expected
    real(dp), intent(in) :: value_expected
    character(*), intent(in), optional :: reason_fragment
    real(dp) :: value
    logical :: ok
    character(:), allocatable :: reason
    call parse_real(text, value, ok, reason)
    call check('parse_real_'//text, ok .eqv. ok_expected, 'ok = '//merge('T', 'F', ok)//', reason "'//reason//'"')
    if (ok .and. ok_expected) call check('parse_real_value_'//text, value == value_expected, table_real(value))
    if (present(reason_fragment)) call check_text_contains('parse_real_reason_'//text, reason, reason_fragment)
  end subroutine expect_number

  subroutine check_text(name, actual, expected)
    character(*), intent(in) :: name, actual, expected
    call check(name, actual == expected, 'got "'//actual//'", expected "'//expected//'"')
  end subroutine check_text

  subroutine expect_valid(name, deck_lines)
    character(*), intent(in) :: name
    character(*), intent(in) :: deck_lines(:)
    character(:), allocatable :: text
    logical :: refused
    call try_read_deck(folder//'/'//name//'.inp', refused, text, deck_lines)
    call check(name, .not. refused, text)
  end subroutine expect_valid

  !> read_deck must fail with `path:line:column: CARD: ...fragment...` (column 0: any).
  subroutine expect_read_error(name, deck_lines, line, column, card, fragment)
    character(*), intent(in) :: name
    character(*), intent(in) :: deck_lines(:)
    integer, intent(in) :: line, column
    character(*), intent(in) :: card, fragment
    character(:), allocatable :: path
    path = folder//'/'//name//'.inp'
    call write_deck(path, deck_lines)
    call expect_error_at(name, path, line, column, card, fragment)
  end subroutine expect_read_error

  subroutine expect_error_at(name, path, line, column, card, fragment)
    character(*), intent(in) :: name, path
    integer, intent(in) :: line, column
    character(*), intent(in) :: card, fragment
    character(:), allocatable :: text
    logical :: refused
    call try_read_deck(path, refused, text)
    call check(name//'_error', refused, 'read_deck accepted '//path)
    if (.not. refused) return
    if (column > 0) then
      call check_text_contains(name//'_location', text, path//':'//integer_text(line)//':'//integer_text(column)//': ')
    else
      call check_text_contains(name//'_location', text, path//':'//integer_text(line)//':')
    end if
    if (len(card) > 0) call check_text_contains(name//'_card', text, ': '//card//': ')
    call check_text_contains(name//'_message', text, fragment)
  end subroutine expect_error_at
end program test_input_guards
