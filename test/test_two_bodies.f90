!> Verification of the second deformable body (BODY SPHERE card:
!> src/cards/visco2d_body_mesh.f90, the curved node-to-segment contact of
!> src/contact/visco2d_contact.f90, src/contact/visco2d_two_bodies.f90):
!>
!>  1. Two equal spheres head on (the Table 1 sphere, E 18.11 MPa, nu 0.219,
!>     rho 756.85, R 36.6 mm, level 2, each at 0.5 m/s) against the existing
!>     run of one sphere on a frictionless rigid plate at half the closing
!>     speed (PLATE Z=0 SLIP RELEASE=YES): the second body's mesh is the
!>     first one mirrored, so every contact node lies over a surface node
!>     (weights 1, 0), and the inelastic projection of two equal masses moving
!>     toward each other at equal speeds is the plate's stop; by the mirror
!>     symmetry the mid-plane does not move. So the runs are the same
!>     discrete problem: the approach of the two centres is 2 alpha_m, and
!>     F_m, q_m, t_alpha_m, the contact radius are the plate's, to the
!>     round-off of the sums (relative 1e-9 over ~700 steps; measured equal
!>     to every printed digit). The contact duration may differ by one step
!>     (DT): a pad-style pair is released at the start of the increment after
!>     its force turns tensile, a plate node within it (visco2d_contact).
!>  2. Hertz with R* = R1 R2/(R1 + R2), 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2,
!>     m* = m1 m2/(m1 + m2) at the approach speed w = v1 - v2: two unequal
!>     spheres (the Table 1 sphere at -0.6 m/s, a 25 mm sphere of E 10 MPa,
!>     nu 0.3, rho 950 at +0.4 m/s), levels 1-3. The code's hertz_* keys are
!>     first checked against the test's own evaluation of the formulas (R1
!>     from the card, the mesh's pole curvature differs by 5e-5: 1e-4). The
!>     finite-body correction, FE/Hertz for alpha_m, F_m and the contact
!>     time, is measured on two equal spheres at the same levels (the same
!>     deck with the second sphere the first's, at +-0.5 m/s, a/R ~ 0.13);
!>     at levels 2 and 3 the unequal pair's ratios follow the equal pair's
!>     to 2 % (measured within 0.9 %: a/R* differs, 0.28 against 0.26, and
!>     the unequal meshes do not match node for node). Level 1 is printed only
!>     (its force ratio is 7 % off: 10 surface segments per half circle).
!>  3. Momentum: without a plate or gravity the z momentum m1 v1 + m2 v2 of
!>     the two centres of mass is constant at every history row to round-off
!>     (1e-12 of m1 |v1|: the internal forces and the contact pairs' equal
!>     and opposite impulses sum to zero, the lumped masses are constant).
!>     Energy: the initial kinetic energy is both bodies' (1e-12), and the
!>     books close over both bodies, balance_error_max_rel below 1e-3
!>     (measured 1.7e-4; the rigid plate's own at level 2 is 1.3e-4). The
!>     elastic spheres rebound with a relative restitution within (0.99, 1]
!>     (measured 0.9994 at level 2: some energy stays in vibration).
!>  4. The BODY card's errors, located at file, line, column and card.
!> Every number is printed in markdown tables. Decks are written to
!> build/test-tmp/test_two_bodies/.
program test_two_bodies
  use visco2d_kinds, only: dp
  use visco2d_error, only: error_t, error_text
  use visco2d_deck, only: deck_t, read_deck
  use visco2d_dynamic, only: solve_dynamic
  use visco2d_hertz, only: hertz_t, hertz_impact
  use visco2d_record, only: record_t
  use visco2d_testing, only: check, check_close, test_summary, write_deck, history_column, summary_real
  use visco2d_test_decks, only: try_read_deck, check_error_location
  implicit none

  character(*), parameter :: folder = 'build/test-tmp/test_two_bodies'
  integer, parameter :: line_length = 100
  character(*), parameter :: apple = 'MATERIAL apple ELASTIC E=18.11e6 NU=0.219 RHO=756.85'
  character(*), parameter :: peach = 'MATERIAL peach ELASTIC E=10e6 NU=0.3 RHO=950'
  real(dp), parameter :: dt = 1.0e-5_dp

  type :: run_t
    character(:), allocatable :: name
    type(record_t) :: record
    logical :: ok = .false.
  end type run_t

  call execute_command_line('mkdir -p '//folder)
  call equal_spheres()
  call unequal_spheres()
  call bad_bodies()
  call test_summary('test_two_bodies')

contains

  !> The deck lines: the Table 1 sphere at level `level` and speed `v1`
  !> (m/s, toward -z), and `extra` (a BODY card, or a PLATE and STOP card).
  function pair_lines(level, v1, extra) result(lines)
    character(*), intent(in) :: level, v1
    character(*), intent(in) :: extra(:)
    character(len=line_length), allocatable :: lines(:)
    lines = [character(len=line_length) :: 'ANALYSIS DYNAMIC', 'GEOMETRY AXISYMMETRIC', apple, peach, &
             'MESH SPHERE R=0.0366 LEVEL='//level//' MAT=apple', 'INITIAL VZ='//v1, 'WILSON THETA=1.4', &
             'TIME DT=1e-5 TEND=20e-3', 'OUTPUT EVERY=1', extra]
  end function pair_lines

  !> Write TITLE + body + END, read and run it (a failed check if it does not run).
  function run_case(name, body) result(run)
    character(*), intent(in) :: name
    character(len=line_length), intent(in) :: body(:)
    type(run_t) :: run
    type(deck_t) :: deck
    type(error_t), allocatable :: error
    character(len=line_length), allocatable :: deck_lines(:)
    run%name = name
    deck_lines = [character(len=line_length) :: 'TITLE '//name, body, 'END']
    call write_deck(folder//'/'//name//'.inp', deck_lines)
    call read_deck(folder//'/'//name//'.inp', deck, error)
    if (.not. allocated(error)) call solve_dynamic(deck, run%record, error)
    if (allocated(error)) then
      call check('run_'//name, .false., error_text(error))
      return
    end if
    run%ok = .true.
  end function run_case

  !> A real summary value of a run (NaN, and a failed check, if absent).
  real(dp) function value_of(run, key) result(x)
    type(run_t), intent(in) :: run
    character(*), intent(in) :: key
    x = summary_real(run%record, key)
  end function value_of

  !> A number in fixed notation with `digits` decimals.
  function fx(x, digits) result(text)
    real(dp), intent(in) :: x
    integer, intent(in) :: digits
    character(:), allocatable :: text
    character(len=32) :: buffer
    character(len=12) :: form
    write(form, '(a,i0,a)') '(f0.', digits, ')'
    write(buffer, form) x
    text = trim(buffer)
  end function fx

  !> A number in scientific notation.
  function ex(x) result(text)
    real(dp), intent(in) :: x
    character(:), allocatable :: text
    character(len=32) :: buffer
    write(buffer, '(es10.3)') x
    text = trim(adjustl(buffer))
  end function ex

  !> 1. Two equal spheres head on against one on the frictionless plate at half the closing speed.
  subroutine equal_spheres()
    type(run_t) :: plate, pair
    character(len=24), parameter :: keys(5) = [character(len=24) :: 'force_max_N', 'q_max_MPa', 't_alpha_max_ms', &
                                               'contact_radius_max_mm', 't_force_max_ms']
    integer :: k
    plate = run_case('equal_plate', pair_lines('2', '-0.5', [character(len=line_length) :: &
                     'PLATE Z=0 SLIP RELEASE=YES', 'STOP AT=SEPARATION']))
    pair = run_case('equal_pair', pair_lines('2', '-0.5', [character(len=line_length) :: &
                    'BODY SPHERE R=0.0366 LEVEL=2 MAT=apple VZ=0.5']))
    if (.not. (plate%ok .and. pair%ok)) return
    print '(a)', ''
    print '(a)', '| equal spheres, level 2 | one on the plate at 0.5 m/s | two head on at +-0.5 m/s |'
    print '(a)', '|---|---|---|'
    print '(a)', '| 2 alpha_m / approach (mm) | '//fx(2*value_of(plate, 'alpha_max_mm'), 6)//' | '// &
      fx(value_of(pair, 'alpha_max_mm'), 6)//' |'
    do k = 1, size(keys)
      print '(a)', '| '//trim(keys(k))//' | '//fx(value_of(plate, trim(keys(k))), 6)//' | '// &
        fx(value_of(pair, trim(keys(k))), 6)//' |'
    end do
    print '(a)', '| contact_duration_ms | '//fx(value_of(plate, 'contact_duration_ms'), 3)//' | '// &
      fx(value_of(pair, 'contact_duration_ms'), 3)//' |'
    print '(a)', '| coefficient_of_restitution | '//fx(value_of(plate, 'coefficient_of_restitution'), 6)//' | '// &
      fx(value_of(pair, 'coefficient_of_restitution'), 6)//' |'
    call check_close('equal spheres: the approach is twice the plate''s alpha_m (1e-9)', &
                     value_of(pair, 'alpha_max_mm'), 2*value_of(plate, 'alpha_max_mm'), 1.0e-9_dp)
    do k = 1, size(keys)
      call check_close('equal spheres: '//trim(keys(k))//' is the plate''s (1e-9)', value_of(pair, trim(keys(k))), &
                       value_of(plate, trim(keys(k))), 1.0e-9_dp)
    end do
    call check('equal spheres: the contact lasts as long as on the plate, to one step', &
               abs(value_of(pair, 'contact_duration_ms') - value_of(plate, 'contact_duration_ms')) <= &
               1.0e3_dp*dt*(1.0_dp + 1.0e-9_dp))
    ! One step later the rebound velocity has changed by dt times the last, tiny, acceleration.
    call check_close('equal spheres: the relative restitution is the plate''s (1e-4)', &
                     value_of(pair, 'coefficient_of_restitution'), value_of(plate, 'coefficient_of_restitution'), &
                     1.0e-4_dp)
  end subroutine equal_spheres

  !> 2.-3. Two unequal spheres head on: Hertz with R*, E*, m*, the finite-body
  !> correction from two equal spheres, momentum and energy.
  subroutine unequal_spheres()
    type(run_t) :: pair(3), equal(3)
    real(dp) :: ratio(3, 3, 2)            ! (alpha, force, time; level; unequal, equal)
    character(len=1) :: level
    integer :: l
    do l = 1, 3
      write(level, '(i1)') l
      pair(l) = run_case('unequal_'//level, pair_lines(level, '-0.6', [character(len=line_length) :: &
                         'BODY SPHERE R=0.025 LEVEL='//level//' MAT=peach VZ=0.4']))
      equal(l) = run_case('equal_'//level, pair_lines(level, '-0.5', [character(len=line_length) :: &
                          'BODY SPHERE R=0.0366 LEVEL='//level//' MAT=apple VZ=0.5']))
      if (.not. (pair(l)%ok .and. equal(l)%ok)) return
      ratio(:, l, 1) = ratios(pair(l))
      ratio(:, l, 2) = ratios(equal(l))
    end do
    call check_reference(pair(2), [18.11e6_dp, 10.0e6_dp], [0.219_dp, 0.3_dp], [0.0366_dp, 0.025_dp], 1.0_dp)
    call check_reference(equal(2), [18.11e6_dp, 18.11e6_dp], [0.219_dp, 0.219_dp], [0.0366_dp, 0.0366_dp], 1.0_dp)
    print '(a)', ''
    print '(a)', '| level | pair | alpha_m FE (mm) | Hertz (mm) | FE/Hertz | F_m FE (N) | Hertz (N) | FE/Hertz | '// &
      't_c FE (ms) | Hertz (ms) | FE/Hertz | restitution | balance_error_max_rel |'
    print '(a)', '|---|---|---|---|---|---|---|---|---|---|---|---|---|'
    do l = 1, 3
      call table_row(l, 'R 36.6 + 25 mm', pair(l), ratio(:, l, 1))
      call table_row(l, 'R 36.6 + 36.6 mm', equal(l), ratio(:, l, 2))
    end do
    do l = 2, 3
      write(level, '(i1)') l
      call check_close('level '//level//': alpha_m/Hertz of the unequal pair follows the equal pair''s (2 %)', &
                       ratio(1, l, 1), ratio(1, l, 2), 0.02_dp)
      call check_close('level '//level//': F_m/Hertz of the unequal pair follows the equal pair''s (2 %)', &
                       ratio(2, l, 1), ratio(2, l, 2), 0.02_dp)
      call check_close('level '//level//': t_c/Hertz of the unequal pair follows the equal pair''s (2 %)', &
                       ratio(3, l, 1), ratio(3, l, 2), 0.02_dp)
    end do
    call check_momentum(pair(2), -0.6_dp, 0.4_dp)
    call check_momentum(equal(2), -0.5_dp, 0.5_dp)
  end subroutine unequal_spheres

  !> FE over Hertz of a run: alpha_m, F_m and the contact duration.
  function ratios(run) result(values)
    type(run_t), intent(in) :: run
    real(dp) :: values(3)
    values = [value_of(run, 'alpha_max_mm')/value_of(run, 'hertz_alpha_max_mm'), &
              value_of(run, 'force_max_N')/value_of(run, 'hertz_force_max_N'), &
              value_of(run, 'contact_duration_ms')/value_of(run, 'hertz_contact_duration_ms')]
  end function ratios

  !> One row of the Hertz table.
  subroutine table_row(level, label, run, ratio)
    integer, intent(in) :: level
    character(*), intent(in) :: label
    type(run_t), intent(in) :: run
    real(dp), intent(in) :: ratio(3)
    character(len=1) :: digit
    write(digit, '(i1)') level
    print '(a)', '| '//digit//' | '//label//' | '//fx(value_of(run, 'alpha_max_mm'), 4)//' | '// &
      fx(value_of(run, 'hertz_alpha_max_mm'), 4)//' | '//fx(ratio(1), 4)//' | '// &
      fx(value_of(run, 'force_max_N'), 2)//' | '//fx(value_of(run, 'hertz_force_max_N'), 2)//' | '// &
      fx(ratio(2), 4)//' | '//fx(value_of(run, 'contact_duration_ms'), 3)//' | '// &
      fx(value_of(run, 'hertz_contact_duration_ms'), 3)//' | '//fx(ratio(3), 4)//' | '// &
      fx(value_of(run, 'coefficient_of_restitution'), 4)//' | '//ex(value_of(run, 'balance_error_max_rel'))//' |'
  end subroutine table_row

  !> The code's two-body Hertz keys against the test's own R*, E*, m* at the
  !> approach speed w (the masses are the run's, m1 = mass_kg, m2 = body2_mass_kg).
  subroutine check_reference(run, young, poisson, radius, speed)
    type(run_t), intent(in) :: run
    real(dp), intent(in) :: young(2), poisson(2), radius(2), speed
    type(hertz_t) :: hertz
    real(dp) :: modulus, reduced_radius, mass(2)
    mass = [value_of(run, 'mass_kg'), value_of(run, 'body2_mass_kg')]
    modulus = 1.0_dp/((1.0_dp - poisson(1)**2)/young(1) + (1.0_dp - poisson(2)**2)/young(2))
    reduced_radius = radius(1)*radius(2)/(radius(1) + radius(2))
    hertz = hertz_impact(modulus, 0.0_dp, reduced_radius, mass(1)*mass(2)/(mass(1) + mass(2)), speed)
    call check_close(run%name//': approach speed w = v2 - v1 at first contact (1e-12)', &
                     value_of(run, 'approach_speed_m_s'), speed, 1.0e-12_dp)
    call check_close(run%name//': hertz_effective_modulus_Pa is E* (1e-12)', &
                     value_of(run, 'hertz_effective_modulus_Pa'), modulus, 1.0e-12_dp)
    call check_close(run%name//': hertz_radius_m is R* (1e-4: R1 from the mesh''s pole)', &
                     value_of(run, 'hertz_radius_m'), reduced_radius, 1.0e-4_dp)
    call check_close(run%name//': hertz_alpha_max_mm (1e-4)', value_of(run, 'hertz_alpha_max_mm'), &
                     1.0e3_dp*hertz%alpha_max, 1.0e-4_dp)
    call check_close(run%name//': hertz_force_max_N (1e-4)', value_of(run, 'hertz_force_max_N'), &
                     hertz%force_max, 1.0e-4_dp)
    call check_close(run%name//': hertz_contact_duration_ms (1e-4)', value_of(run, 'hertz_contact_duration_ms'), &
                     1.0e3_dp*hertz%duration, 1.0e-4_dp)
  end subroutine check_reference

  !> 3. The z momentum of both centres of mass at every history row, the
  !> initial kinetic energy of both bodies, the energy books, the restitution.
  subroutine check_momentum(run, v1, v2)
    type(run_t), intent(in) :: run
    real(dp), intent(in) :: v1, v2
    real(dp), allocatable :: first(:), second(:), momentum(:)
    real(dp) :: m1, m2
    character(len=12) :: rows
    m1 = value_of(run, 'mass_kg')
    m2 = value_of(run, 'body2_mass_kg')
    first = history_column(run%record, 'vz_cm_m_s')
    second = history_column(run%record, 'body2_vz_cm_m_s')
    call check(run%name//': history has both bodies'' velocities', size(first) > 100 .and. size(second) == size(first))
    if (size(first) == 0 .or. size(second) /= size(first)) return
    momentum = m1*first + m2*second
    write(rows, '(i0)') size(momentum)
    print '(a)', run%name//': momentum m1 v1 + m2 v2 = '//ex(m1*v1 + m2*v2)//' kg m/s at the start, largest change '// &
      ex(maxval(abs(momentum - (m1*v1 + m2*v2))))//' over '//trim(rows)//' rows'
    call check(run%name//': momentum constant at every row (1e-12 of m1 |v1|)', &
               maxval(abs(momentum - (m1*v1 + m2*v2))) <= 1.0e-12_dp*m1*abs(v1))
    call check_close(run%name//': initial kinetic energy is both bodies'' (1e-12)', value_of(run, 'initial_kinetic_J'), &
                     0.5_dp*m1*v1**2 + 0.5_dp*m2*v2**2, 1.0e-12_dp)
    call check(run%name//': energy books close over both bodies (balance_error_max_rel < 1e-3)', &
               abs(value_of(run, 'balance_error_max_rel')) < 1.0e-3_dp)
    call check(run%name//': elastic rebound, relative restitution in (0.99, 1]', &
               value_of(run, 'coefficient_of_restitution') > 0.99_dp .and. &
               value_of(run, 'coefficient_of_restitution') <= 1.0_dp)
  end subroutine check_momentum

  !> 4. The BODY card's errors.
  subroutine bad_bodies()
    character(len=line_length), allocatable :: base(:), changed(:)
    base = [character(len=line_length) :: 'TITLE bad body', 'ANALYSIS DYNAMIC', 'GEOMETRY AXISYMMETRIC', apple, &
            peach, 'MESH SPHERE R=0.0366 LEVEL=1 MAT=apple', 'INITIAL VZ=-0.5', 'TIME DT=1e-5 TEND=2e-3', &
            'BODY SPHERE R=0.025 MAT=peach VZ=0.4', 'END']                             ! BODY on line 9
    call expect_error('body_shape', with(base, 9, 'BODY CUBE R=0.025 MAT=peach'), 9, 6, 'BODY', &
                      'shape must be SPHERE (the only one so far), got "CUBE"')
    call expect_error('body_without_radius', with(base, 9, 'BODY SPHERE MAT=peach'), 9, 1, 'BODY', &
                      'missing field R=')
    call expect_error('body_without_material', with(base, 9, 'BODY SPHERE R=0.025'), 9, 1, 'BODY', &
                      'missing field MAT=')
    call expect_error('body_radius_negative', with(base, 9, 'BODY SPHERE R=-0.025 MAT=peach'), 9, 13, 'BODY', 'R')
    call expect_error('body_level', with(base, 9, 'BODY SPHERE R=0.025 LEVEL=9 MAT=peach'), 9, 21, 'BODY', &
                      'LEVEL must be in 1..7, got 9')
    call expect_error('body_gap_negative', with(base, 9, 'BODY SPHERE R=0.025 MAT=peach GAP=-0.001'), 9, 31, 'BODY', &
                      'GAP must be 0 or more')
    call expect_error('body_contact_kind', with(base, 9, 'BODY SPHERE GLUED R=0.025 MAT=peach'), 9, 13, 'BODY', &
                      'contact kind must be SLIP or STICK, got "GLUED"')
    call expect_error('body_release', with(base, 9, 'BODY SPHERE R=0.025 MAT=peach RELEASE=MAYBE'), 9, 31, 'BODY', &
                      'RELEASE must be YES or NO, got "MAYBE"')
    call expect_error('body_unknown_field', with(base, 9, 'BODY SPHERE R=0.025 MAT=peach FOO=1'), 9, 31, 'BODY', &
                      'unknown field FOO')
    call expect_error('body_material_undefined', with(base, 9, 'BODY SPHERE R=0.025 MAT=plum'), 9, 21, 'BODY', &
                      'the second body''s material PLUM is not defined by a MATERIAL card')
    call expect_error('body_material_without_density', with(base, 5, 'MATERIAL peach ELASTIC E=10e6 NU=0.3'), 5, 0, &
                      'MATERIAL', 'has no density')
    call expect_error('body_twice', [base(1:9), base(9:)], 10, 1, 'BODY', &
                      'only one BODY card is allowed (first on line 9)')
    call expect_error('body_with_plate', [base(1:9), 'PLATE Z=0 SLIP', base(10)], 9, 0, 'BODY', &
                      'BODY with a PLATE (line 10) is not available yet')
    call expect_error('body_with_pad', [base(1:9), 'PLATE Z=0 SLIP', &
                      'PAD THICKNESS=0.01 MAT=peach', base(10)], 9, 0, 'BODY', 'BODY with a PLATE')
    call expect_error('body_with_gravity', [base(1:9), 'GRAVITY G=9.8', base(10)], 9, 0, 'BODY', &
                      'BODY with GRAVITY (line 10) is not available yet')
    changed = with(base, 2, 'ANALYSIS STATIC')
    call expect_error('body_static', [changed(1:6), changed(9:)], 7, 0, 'BODY', 'BODY needs ANALYSIS DYNAMIC')
    call expect_error('body_plane_strain', with(base, 3, 'GEOMETRY PLANESTRAIN'), 9, 0, 'BODY', &
                      'BODY needs GEOMETRY AXISYMMETRIC')
    call expect_error('body_stop_maxdeformation', [base(1:9), 'STOP AT=MAXDEFORMATION', base(10)], 10, 6, 'STOP', &
                      'STOP AT=MAXDEFORMATION needs a PLATE')
    changed = with(base, 9, 'BODY SPHERE R=0.025 MAT=peach RELEASE=NO')
    call expect_error('body_stop_separation_held', [changed(1:9), 'STOP AT=SEPARATION', changed(10)], 10, 6, 'STOP', &
                      'STOP AT=SEPARATION needs BODY ... RELEASE=YES')
    call expect_error('body_plastic', [base(1:5), 'PLASTIC YIELD=1e5 TANGENT=0', base(6:)], 6, 0, 'PLASTIC', &
                      'with a second BODY (line 10) is not available yet')
  end subroutine bad_bodies

  !> `lines` with line `k` replaced by `text`.
  function with(lines, k, text) result(changed)
    character(len=line_length), intent(in) :: lines(:)
    integer, intent(in) :: k
    character(*), intent(in) :: text
    character(len=line_length), allocatable :: changed(:)
    changed = lines
    changed(k) = text
  end function with

  !> The deck is refused at file:line:column: CARD: ...fragment...
  subroutine expect_error(name, deck_lines, line, column, card, fragment)
    character(*), intent(in) :: name
    character(len=line_length), intent(in) :: deck_lines(:)
    integer, intent(in) :: line, column
    character(*), intent(in) :: card, fragment
    character(:), allocatable :: path, text
    logical :: refused
    path = folder//'/'//name//'.inp'
    call try_read_deck(path, refused, text, deck_lines)
    call check(name//'_error', refused, 'read_deck accepted '//path)
    if (refused) call check_error_location(name, text, path, line, column, card, fragment)
  end subroutine expect_error
end program test_two_bodies
