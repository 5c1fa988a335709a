!> The sensor of PROBE ... RADIUS= (visco2d_impact's sensor_acceleration,
!> the history columns <name>_sensor_ar_m_s2 / _sensor_az_m_s2 and the
!> summary keys probe_<name>_sensor_*): the mass-weighted mean acceleration
!> of the nodes within the radius.
!>
!>  1. Free flight under gravity (a block, no plate): every node falls with
!>     a = -g, so a sensor reads a_z = -g and a_r = 0 at every row, to the
!>     round-off of the solve (each node's a_z is -g to ~1e-11 relative;
!>     checked at 1e-9, as inputs/free_flight.inp's EXPECT cards); its region is the
!>     nodes within the radius (counted here from the grid); a sensor that
!>     covers the whole body has the body's mass.
!>  2. An impact (the Fig. 2 apple, a 10 mm accelerometer: RADIUS = 5 mm):
!>     a sensor covering the whole body reads the centre-of-mass
!>     acceleration az_cm_m_s2 at every row (the same mass-weighted mean,
!>     1e-9 relative to its peak); on levels 1 and 2 (dt 5e-6 s) a sensor
!>     that holds more than its node has a peak closer to the centre-of-mass
!>     peak than the node's (the node's ringing averages out), and one that
!>     holds only its node reads that node (peaks equal to 1e-12): on the
!>     default contact grid (GRADE 4.5) the node nearest the centre is
!>     0.68 mm from it and the next 5.5 mm at level 1, so the 5 mm sensor
!>     holds 1 node there, 3 at level 2 (on the GRADE 2.5 grid 2 and 4, and
!>     level 1 was checked 'nearer'); level 2's sensor must hold more than
!>     one node, so that 'nearer' is checked at least once; from level 1 to
!>     2 the sensor's peak moves toward the centre of mass's.
!>     The summary says what a sensor reads (probe_<name>_sensor_reads): the
!>     mean acceleration of its region, not the body's F/M, naming
!>     accel_cm_max_g (the sensor tends to about 1.11-1.13 x F/M - g at the
!>     centre of this apple, the arrests' stress waves, doc/verification.md:
!>     a user must not read it as the rigid-body deceleration).
!>  3. A bad RADIUS= (zero, negative) and RADIUS= outside DYNAMIC are refused
!>     at the card with the column of RADIUS=.
program test_sensor
  use visco2d_kinds, only: dp
  use visco2d_error, only: error_t, error_text
  use visco2d_deck, only: deck_t, read_deck
  use visco2d_dynamic, only: solve_dynamic
  use visco2d_record, only: record_t
  use visco2d_strings, only: integer_text
  use visco2d_testing, only: check, check_close, check_text_contains, test_summary, write_deck, &
                             history_column, summary_real
  use visco2d_expect, only: summary_value
  implicit none

  character(*), parameter :: folder = 'build/test-tmp/test_sensor'
  integer, parameter :: line_length = 100
  real(dp), parameter :: g_unit = 9.80665_dp

  call execute_command_line('mkdir -p '//folder)
  call test_free_flight()
  call test_impact()
  call test_refused()
  call test_summary('test_sensor')

contains

  !> Write TITLE + body + END, read and run it; .false. (and a failed check) if it does not run.
  logical function run_deck(name, body, record) result(ok)
    character(*), intent(in) :: name
    character(len=line_length), intent(in) :: body(:)
    type(record_t), intent(out) :: record
    type(deck_t) :: deck
    type(error_t), allocatable :: error
    character(len=line_length), allocatable :: lines(:)
    allocate(lines(size(body) + 2))
    lines(1) = 'TITLE '//name
    lines(2:size(body) + 1) = body
    lines(size(body) + 2) = 'END'
    call write_deck(folder//'/'//name//'.inp', lines)
    call read_deck(folder//'/'//name//'.inp', deck, error)
    if (.not. allocated(error)) call solve_dynamic(deck, record, error)
    ok = .not. allocated(error)
    if (.not. ok) call check('run_'//name, .false., error_text(error))
  end function run_deck

  !> 1. Free flight: a = -g exactly, at every row, for a small and a whole-body sensor.
  subroutine test_free_flight()
    type(record_t) :: record
    real(dp), allocatable :: az(:), ar(:), whole(:)
    print '(a)', '## 1. Free flight under gravity (MESH RECT 2 x 2, 10 mm, G = 9.8)'
    if (.not. run_deck('free_flight', [character(len=line_length) :: 'ANALYSIS DYNAMIC', 'GEOMETRY AXISYMMETRIC', &
        'MATERIAL flesh ELASTIC E=1e6 NU=0.3 RHO=800', 'MESH RECT R0=0 R1=0.01 Z0=0 Z1=0.01 NR=2 NZ=2', &
        'INITIAL VZ=-1', 'GRAVITY G=9.8', 'TIME DT=1e-5 TEND=1e-3', 'OUTPUT EVERY=10', &
        'PROBE middle R=0 Z=0.005 RADIUS=0.005', 'PROBE whole R=0 Z=0.005 RADIUS=1'], record)) return
    az = history_column(record, 'middle_sensor_az_m_s2')
    ar = history_column(record, 'middle_sensor_ar_m_s2')
    whole = history_column(record, 'whole_sensor_az_m_s2')
    call check('free flight: rows', size(az) > 10, integer_text(size(az))//' rows')
    call check('free flight: sensor a_z = -g at every row (1e-9 relative)', &
               all(abs(az + 9.8_dp) <= 1.0e-9_dp*9.8_dp), 'worst '//real_text(maxval(abs(az + 9.8_dp))))
    call check('free flight: sensor a_r = 0 at every row', all(abs(ar) <= 1.0e-9_dp*9.8_dp), &
               'worst '//real_text(maxval(abs(ar))))
    call check('free flight: whole-body sensor a_z = -g', all(abs(whole + 9.8_dp) <= 1.0e-9_dp*9.8_dp))
    ! Nodes of the 2 x 2 grid (spacing 5 mm) within 5 mm of (0, 5 mm): (0, 0), (0, 5), (0, 10), (5, 5) mm.
    call check_close('free flight: the sensor holds the 4 nodes within 5 mm', &
                     summary_real(record, 'probe_middle_sensor_nodes'), 4.0_dp, 0.0_dp)
    call check_close('free flight: the sensor holds all 9 nodes at RADIUS=1', &
                     summary_real(record, 'probe_whole_sensor_nodes'), 9.0_dp, 0.0_dp)
    call check_close('free flight: the whole-body sensor has the body mass', &
                     summary_real(record, 'probe_whole_sensor_mass_kg'), summary_real(record, 'mass_kg'), 1.0e-12_dp)
  end subroutine test_free_flight

  !> 2. The Fig. 2 apple: the whole-body sensor is the centre of mass; the 10 mm sensor converges where the node rings.
  subroutine test_impact()
    type(record_t) :: record
    real(dp) :: node(2), sensor(2), cm(2), change_node, change_sensor
    integer :: nodes(2)
    real(dp), allocatable :: whole(:), az_cm(:)
    integer :: level
    print '(a)', '## 2. The Fig. 2 apple (25.4 mm drop, STICK, dt 5e-6 s): centre node, 10 mm sensor, centre of mass'
    print '(a)', '| level | centre node peak (g) | sensor peak, RADIUS 5 mm (g) | sensor nodes | centre of mass peak (g) |'
    print '(a)', '|---|---|---|---|---|'
    do level = 1, 2
      if (.not. run_deck('apple_L'//integer_text(level), [character(len=line_length) :: 'ANALYSIS DYNAMIC', &
          'GEOMETRY AXISYMMETRIC', 'MATERIAL golden VISCOELASTIC K=1.756e6 RHO=790', 'PRONY G=0.636e6 BETA=0.000347', &
          'PRONY G=0.111e6 BETA=0.0409', 'PRONY G=0.208e6 BETA=1.121', 'PRONY G=0.099e6 BETA=35.26', &
          'MESH SPHERE R=0.035 LEVEL='//integer_text(level), 'DROP HEIGHT=0.0254', 'GRAVITY G=9.8', &
          'TIME DT=5e-6 TEND=8e-3', 'PLATE Z=0 STICK', 'STOP AT=MAXDEFORMATION', &
          'PROBE accelerometer R=0 Z=0.035 RADIUS=0.005', 'PROBE whole R=0 Z=0.035 RADIUS=1'], record)) return
      call check_text_contains('impact level '//integer_text(level)//': the summary says the sensor is not F/M', &
                               summary_value(record, 'probe_accelerometer_sensor_reads'), 'not the body''s F/M')
      call check_text_contains('impact level '//integer_text(level)//': the sensor note names accel_cm_max_g', &
                               summary_value(record, 'probe_accelerometer_sensor_reads'), 'accel_cm_max_g')
      node(level) = summary_real(record, 'accel_center_max_g')
      sensor(level) = summary_real(record, 'probe_accelerometer_sensor_accel_max_g')
      cm(level) = summary_real(record, 'accel_cm_max_g')
      print '(a, i0, 2(a, f0.2), a, i0, a, f0.2, a)', '| ', level, ' | ', node(level), ' | ', sensor(level), ' | ', &
        nint(summary_real(record, 'probe_accelerometer_sensor_nodes')), ' | ', cm(level), ' |'
      whole = history_column(record, 'whole_sensor_az_m_s2')
      az_cm = history_column(record, 'az_cm_m_s2')
      if (size(whole) /= size(az_cm) .or. size(whole) == 0) cycle
      call check('impact level '//integer_text(level)//': whole-body sensor = centre of mass at every row (1e-9 of its peak)', &
                 all(abs(whole - az_cm) <= 1.0e-9_dp*maxval(abs(az_cm))), &
                 'worst '//real_text(maxval(abs(whole - az_cm))))
      nodes(level) = nint(summary_real(record, 'probe_accelerometer_sensor_nodes'))
      if (nodes(level) == 1) then
        call check_close('impact level '//integer_text(level)//': a sensor of one node reads that node', &
                         sensor(level), node(level), 1.0e-12_dp)
      else
        call check('impact level '//integer_text(level)//': the sensor is nearer the centre of mass than the node', &
                   abs(sensor(level) - cm(level)) < abs(node(level) - cm(level)), 'sensor '// &
                   real_text(sensor(level))//' g, node '//real_text(node(level))//' g, centre of mass '// &
                   real_text(cm(level))//' g')
      end if
    end do
    call check('impact level 2: the 10 mm sensor holds more than its node', nodes(2) > 1, &
               integer_text(nodes(2))//' node(s)')
    ! The sensor's peak falls as the mesh is refined (measured on levels 1-5:
    ! 75.0, 70.2, 69.6, 49.4, 45.6 g on the legacy grid, doc/verification.md),
    ! toward a limit above the centre of mass's 41.1 g (about 1.11-1.13 x it
    ! on the default grid, levels 3-5 at dt 5e-6 s), while the node's does
    ! not converge; with only 1 and 3 nodes in the 10 mm sensor at levels 1
    ! and 2 (default grid; measured 62.23 -> 59.63 g, node 62.23 -> 74.80 g,
    ! centre of mass 40.64 -> 41.32 g), the distance to the centre of mass is
    ! what can be checked here.
    change_node = abs(node(2) - node(1))/node(2)
    change_sensor = abs(sensor(2) - sensor(1))/sensor(2)
    call check('impact: levels 1 -> 2 bring the sensor peak nearer the centre-of-mass peak', &
               abs(sensor(2) - cm(2)) < abs(sensor(1) - cm(1)), 'sensor '//real_text(sensor(1))//' -> '// &
               real_text(sensor(2))//' g, centre of mass '//real_text(cm(1))//' -> '//real_text(cm(2))//' g (node '// &
               'change '//real_text(change_node)//', sensor change '//real_text(change_sensor)//')')
  end subroutine test_impact

  !> 3. Refused RADIUS= values.
  subroutine test_refused()
    print '(a)', '## 3. Refused RADIUS='
    call expect_refused('radius_zero', 'ANALYSIS DYNAMIC', 'PROBE s R=0 Z=0 RADIUS=0', 'must be positive')
    call expect_refused('radius_negative', 'ANALYSIS DYNAMIC', 'PROBE s R=0 Z=0 RADIUS=-0.001', 'must be positive')
    call expect_refused('radius_static', 'ANALYSIS STATIC', 'PROBE s R=0 Z=0 RADIUS=0.001', 'needs ANALYSIS DYNAMIC')
  end subroutine test_refused

  subroutine expect_refused(name, analysis, probe, fragment)
    character(*), intent(in) :: name, analysis, probe, fragment
    type(deck_t) :: deck
    type(error_t), allocatable :: error
    character(:), allocatable :: text
    character(len=line_length), allocatable :: lines(:)
    lines = [character(len=line_length) :: 'TITLE '//name, analysis, 'GEOMETRY AXISYMMETRIC', &
      'MATERIAL flesh ELASTIC E=1e6 NU=0.3 RHO=800', 'MESH RECT R0=0 R1=0.01 Z0=0 Z1=0.01 NR=2 NZ=2', 'FIX BOTTOM Z']
    if (analysis /= 'ANALYSIS STATIC') lines = [character(len=line_length) :: lines, 'TIME DT=1e-5 TEND=1e-4']
    lines = [character(len=line_length) :: lines, probe, 'END']
    call write_deck(folder//'/'//name//'.inp', lines)
    call read_deck(folder//'/'//name//'.inp', deck, error)
    if (.not. allocated(error)) then
      call check(name//' refused', .false., 'the deck was read')
      return
    end if
    text = error_text(error)
    call check_text_contains(name//': message', text, fragment)
    call check_text_contains(name//': located at RADIUS=', text, ':'//integer_text(size(lines) - 1)//':'// &
                             integer_text(index(probe, 'RADIUS'))//': PROBE:')
  end subroutine expect_refused

  function real_text(x) result(text)
    real(dp), intent(in) :: x
    character(:), allocatable :: text
    character(len=32) :: buffer
    write(buffer, '(es12.4)') x
    text = trim(adjustl(buffer))
  end function real_text
end program test_sensor
