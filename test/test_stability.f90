!> Hard cases stay numerically stable: Wilson-theta (eqs. [26]-[42]) at huge
!> steps, near-incompressible material (standard and B-bar elements),
!> extreme relaxation times (eqs. [21]-[24]), a run of 1e5 steps, a very
!> soft material, and the conditionally stable theta = 1.0 (detected), also
!> in an impact whose plate reactions grow with the blow-up (case 7).
!>
!> Every dynamic case checks that each history value and snapshot field is
!> finite (ieee_is_finite), that the energy stays bounded,
!>   kinetic + strain <= (external work + gravity work + initial kinetic) (1 + tol)
!> at every history row, and that dissipated_J >= -round-off; then its own physics.
!>
!> The workhorse is a column (plane strain, 0.0025 m x L = 0.2 m, MESH RECT
!> NR=1 NZ=40) confined laterally (FIX INNER R, FIX OUTER R), fixed at the
!> bottom, under a pressure p on the top: a 1-D bar with the constrained
!> modulus M = K + 4G/3, static top displacement u = -p L/M (exact in the
!> bilinear element: the field is linear), P-wave speed c_p = sqrt(M/rho),
!> lowest period T1 = 4 L/c_p.
!>
!> The explicit critical step is estimated as dt_crit = h_min/c_p with h_min =
!> 0.0025 m the smallest element side (not an eigenvalue computation). With
!> the lateral dofs fixed the column is a 1-D chain of h = 0.005 m, whose
!> highest frequency is omega_max = 2 c_p/h, T_min = pi h/c_p: dt_crit is
!> half of the true central-difference limit 2/omega_max, so "1000 dt_crit"
!> is at least 1000 times beyond the explicit limit.
!>
!> Energy tolerance: the exact elastic solution conserves energy (ratio 1
!> under a constant load) and Wilson-theta (theta >= 1.37) damps every mode
!> (spectral radius < 1), so a run started from rest stays at or below
!> ratio 1: measured 0.72 .. 0.9996 over all the cases here (theta = 1.0 at
!> a small step: 0.9999). tol = 1e-3 leaves room only for the O((omega dt)^2)
!> oscillation of the physical energy within the resolved modes; the
!> overshoot of the default start below (E/W = 3.4 at DT = 10 dt_crit) is
!> three orders of magnitude beyond it. Round-off:
!> dissipated_J of an elastic body is the trapezoidal internal work minus
!> the stored energy, identical in exact arithmetic for a linear force; its
!> round-off is about 1e-16 of the energy per step (measured >= -6e-15 over
!> 1e5 steps), so -1e-9 of the input energy leaves a wide margin.
!>
!> Every dynamic run starts from rest (INITIAL AZ=0 AR=0: u = v = a = 0,
!> the load acting from t = 0+), because of this FINDING (see the report;
!> not a test failure): a load applied suddenly at t = 0 with the initial
!> acceleration from equilibrium (the default start) makes Wilson-theta
!> overshoot in its first step when DT is above the shortest periods. For
!> omega dt -> infinity one step gives
!>   u_1 = (1 - 1/theta^3) u_0 + (1 - 1/theta^2) v_0 dt + (1 - 1/theta)/2 a_0 dt^2,
!> so the large initial acceleration a_0 = 2 p/(rho h) of the loaded nodes
!> becomes a displacement 0.143 a_0 dt^2 at theta = 1.4 whatever the
!> stiffness (the known displacement overshoot of Wilson-theta, Hilber and
!> Hughes 1978). On the column the energy ratio after step 1 is measured as
!> ~3.4e-2 (DT/dt_crit)^2 (3.4 at DT = 10 dt_crit: checked to be transient
!> below); it decays by the spectral radius (0.778 per step at omega dt ->
!> infinity). visco2d_dynamic's instability guard therefore widens its limit
!> (100 x the input energy) by 2 ((1 - 1/theta^2) omega_max dt)^2, with
!> omega_max from a Gershgorin bound; the default start at 1000 dt_crit must
!> run, and its overshoot must die out. (Ramping the load over the
!> first step was measured too: Wilson-theta extrapolates the load to
!> R_tau = theta p in that step and the energy ratio reaches 1.084.)
program test_stability
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use visco2d_kinds, only: dp
  use visco2d_error, only: error_t, error_text
  use visco2d_deck, only: deck_t, read_deck
  use visco2d_dynamic, only: solve_dynamic
  use visco2d_static, only: static_solution_t, solve_static
  use visco2d_record, only: record_t
  use visco2d_driver, only: run_deck
  use visco2d_system, only: directory_exists
  use visco2d_testing, only: check, check_close, check_text_contains, test_summary, write_deck, &
                             history_column, history_last, history_index, exact_text
  use visco2d_strings, only: integer_text
  implicit none

  character(*), parameter :: folder = 'build/test-tmp/test_stability'
  real(dp), parameter :: column_length = 0.2_dp, column_width = 0.0025_dp
  ! The thick cylinder (quarter ring) and the cantilever block of case 2: G, internal pressure, radii.
  real(dp), parameter :: ring_shear = 1.0e6_dp, ring_pressure = 1.0e4_dp, ring_a = 0.01_dp, ring_b = 0.02_dp
  real(dp), parameter :: young1 = 18.11e6_dp, poisson1 = 0.219_dp, density1 = 756.85_dp   ! Table 1
  !> Spectral radius of Wilson-theta (theta = 1.4) for omega dt -> infinity,
  !> the largest over omega dt >= 3 (eigenvalues of the 3 x 3 step matrix of
  !> (u, v dt, a dt^2), computed once for this test: 0.762 at omega dt = 3,
  !> 0.562 at 10, 0.7757 at 100, 0.77844 at infinity).
  real(dp), parameter :: rho_infinity = 0.7785_dp
  character(len=240) :: table(20)
  integer :: table_rows = 0
  integer :: k

  call execute_command_line('mkdir -p '//folder)

  call case_large_step()
  call case_incompressible_static()
  call case_incompressible_dynamic()
  call case_relaxation_times()
  call case_long_run()
  call case_soft_material()
  call case_conditional_theta()
  call case_diverging_impact()

  print '(a)', ''
  print '(a)', 'case | what it showed'
  print '(a)', (trim(table(k)), k = 1, table_rows)
  print '(a)', ''
  call test_summary('test_stability')

contains

  ! ------------------------------------------------------------------ case 1

  !> theta = 1.4, DT = 1000 dt_crit: bounded, finite, and the solution tends
  !> to the static one (the fundamental has dt/T1 = 3.1, far beyond any
  !> resolution: the numerical damping removes the vibration).
  subroutine case_large_step()
    type(deck_t) :: deck
    type(record_t) :: record, default_record
    type(static_solution_t) :: solution
    type(error_t), allocatable :: error
    logical :: ok
    real(dp) :: modulus, dt_crit, dt, u_static, u_end, ratio, static_error, tolerance, overshoot, late_ratio
    real(dp), allocatable :: stored(:), input(:)
    character(:), allocatable :: outcome
    character(len=100), allocatable :: material(:)
    integer, parameter :: nsteps = 80
    real(dp), parameter :: pressure = 1.0e5_dp

    material = [elastic_line(young1, poisson1, density1)]
    modulus = constrained_modulus(young1, poisson1)
    dt_crit = column_width/sqrt(modulus/density1)
    dt = 1000.0_dp*dt_crit

    call run_static('case1_static', column_deck('STATIC', material, 40, pressure), deck, solution, ok)
    if (.not. ok) return
    u_static = top_displacement(deck, solution)
    ! The bilinear element represents the linear field u_z = -p z/M exactly: round-off only (1e-10).
    call check_close('case 1: static column top u_z = -p L/M', u_static, -pressure*column_length/modulus, 1.0e-10_dp)

    ! Start from rest: u = v = a = 0, the load acting from t = 0+.
    call run_dynamic('case1_rest', column_deck('DYNAMIC', material, 40, pressure, 1.4_dp, dt, nsteps*dt, 1), &
                     deck, record, ok)
    if (.not. ok) return
    call check_bounded('case 1 (theta 1.4, DT = 1000 dt_crit, from rest)', record, 1.0e-3_dp, ratio)
    u_end = history_last(record, 'top_uz_m')
    static_error = abs(u_end - u_static)/abs(u_static)
    ! The error e_n = u_n - u_static is a free vibration, damped by the
    ! spectral radius of each mode (<= 0.7785 for omega dt >= 3; the
    ! fundamental has omega dt = 2 pi dt/T1 = 19.6): |e_n| <= kappa rho^n |e_0|,
    ! e_0 = -u_static, kappa = 10 for the transient growth of the non-normal
    ! 3 x 3 step matrix. n = 80: 10 x 0.7785^80 = 2.0e-8 (measured 2.1e-10).
    tolerance = 10.0_dp*rho_infinity**nsteps
    call check_close('case 1: after 80 steps of 1000 dt_crit the top u_z equals the static one', &
                     u_end, u_static, tolerance)
    print '(a, es10.3, a, es10.3)', '  case 1 from rest: |u_end - u_static|/|u_static| = ', static_error, &
      ', bound ', tolerance

    ! The default start (a_0 from equilibrium, a sudden load): Wilson-theta's
    ! first-step overshoot (header) is not an instability: the run must go
    ! on, stay finite, and the overshoot must die out (0.78^40 = 5e-5 over
    ! the first half, as below).
    call write_deck(folder//'/case1_default.inp', column_deck('DYNAMIC', material, 40, pressure, 1.4_dp, dt, &
                    nsteps*dt, 1, from_rest=.false.))
    call read_deck(folder//'/case1_default.inp', deck, error)
    if (.not. allocated(error)) call solve_dynamic(deck, default_record, error)
    call check('case 1: the default (equilibrium a_0) start at DT = 1000 dt_crit is not stopped as unstable', &
               .not. allocated(error))
    if (allocated(error)) then
      print '(a)', '  case 1 default start (sudden load, a_0 from equilibrium): '//error_text(error)
      outcome = 'stopped as "unstable"'
    else
      call check('case 1: the default (equilibrium a_0) start ends with finite values', &
                 all(ieee_is_finite(default_record%history(:, 1:default_record%nrow))))
      stored = history_column(default_record, 'kinetic_J') + history_column(default_record, 'strain_J')
      input = history_column(default_record, 'external_work_J')
      print '(a, es11.3, a, es11.3)', '  case 1 default start, DT = 1000 dt_crit: E/W after step 1 ', &
        stored(2)/input(2), ', max over the second half ', maxval(stored(nsteps/2 + 1:)/input(nsteps/2 + 1:))
      call check('case 1: default start at DT = 1000 dt_crit, the overshoot is transient (E/W <= 1 + 1e-3 '// &
                 'over the second half)', maxval(stored(nsteps/2 + 1:)/input(nsteps/2 + 1:)) <= 1.0_dp + 1.0e-3_dp)
      outcome = 'ran; E/W '//num3(stored(2)/input(2))//' after step 1, '// &
                num3(maxval(stored(nsteps/2 + 1:)/input(nsteps/2 + 1:)))//' late'
    end if

    ! The same default start at DT = 10 dt_crit, where the overshoot stays
    ! under the guard: it is transient. The ratio after step 1 is printed
    ! (~3.4 = 3.4e-2 x 10^2); over the second half of the 80 steps it is
    ! back below 1 + 1e-3 (it decays by the spectral radius, <= 0.78 per
    ! step in energy amplitude, 0.78^40 = 5e-5).
    call run_dynamic('case1_default_10', column_deck('DYNAMIC', material, 40, pressure, 1.4_dp, 10.0_dp*dt_crit, &
                     nsteps*10.0_dp*dt_crit, 1, from_rest=.false.), deck, default_record, ok)
    if (ok) then
      stored = history_column(default_record, 'kinetic_J') + history_column(default_record, 'strain_J')
      input = history_column(default_record, 'external_work_J')
      overshoot = stored(2)/input(2)
      late_ratio = maxval(stored(nsteps/2 + 1:)/input(nsteps/2 + 1:))
      print '(a, es11.3, a, es11.3)', '  case 1 default start, DT = 10 dt_crit: E/W after step 1 ', overshoot, &
        ', max over the second half ', late_ratio
      call check('case 1: default start at DT = 10 dt_crit, the first-step overshoot is transient (E/W <= 1 + 1e-3 '// &
                 'over the second half)', late_ratio <= 1.0_dp + 1.0e-3_dp .and. all(ieee_is_finite(stored)))
    end if

    call add_row('1 theta=1.4 DT=1000 dt_crit (from rest)', 'max E/W '//num3(ratio)//'; |u-u_static|/u_static '// &
                 num3(static_error)//' after 80 steps')
    call add_row('1 same, sudden load + equilibrium a_0', outcome//'; at DT = 10 dt_crit E/W = '// &
                 num3(overshoot)//' after step 1, '//num3(late_ratio)//' late')
  end subroutine case_large_step

  ! ------------------------------------------------------------------ case 2a

  !> Near-incompressible (nu = 0.4999, K/G = 5000): the thick cylinder
  !> against Lame and a cantilever block against a converged reference,
  !> STANDARD vs BBAR; the locking warning of the deck reader.
  subroutine case_incompressible_static()
    real(dp) :: error_std3, error_bbar3, error_std5, error_bbar5, bulk, u_exact, u_check, poisson
    real(dp) :: tip(4), reference3, reference5, beam5, fine(2)
    type(deck_t) :: deck
    type(error_t), allocatable :: error
    integer :: k
    logical :: warned

    ! The plane-strain Lame bore displacement, u(a) = p a/(b^2 - a^2) [a^2/(2(K + G/3)) + b^2/(2G)],
    ! against the textbook form (1 + nu)/E A ((1 - 2 nu) a + b^2/a), A = p a^2/(b^2 - a^2)
    ! (test_lame's), for nu = 0.3: the same number to round-off.
    poisson = 0.3_dp
    bulk = bulk_of(ring_shear, poisson)
    u_exact = lame_bore(ring_pressure, ring_a, ring_b, ring_shear, bulk)
    u_check = (1.0_dp + poisson)/(2.0_dp*ring_shear*(1.0_dp + poisson))*ring_pressure*ring_a**2/(ring_b**2 - ring_a**2)* &
              ((1.0_dp - 2.0_dp*poisson)*ring_a + ring_b**2/ring_a)
    call check_close('case 2a: Lame bore formula in K, G equals the (1+nu)/E form (nu = 0.3)', u_exact, u_check, &
                     1.0e-14_dp)

    error_std3 = ring_error('STANDARD', 0.3_dp)
    error_bbar3 = ring_error('BBAR', 0.3_dp)
    error_std5 = ring_error('STANDARD', 0.4999_dp)
    error_bbar5 = ring_error('BBAR', 0.4999_dp)
    print '(a, 4es11.3)', '  case 2a ring NR=NT=8 bore errors (signed, FE/exact - 1): std 0.3, bbar 0.3, std '// &
      '0.4999, bbar 0.4999 =', error_std3, error_bbar3, error_std5, error_bbar5
    ! nu = 0.3 gives the mesh error of this 8 x 8 ring (~0.5 %, the O(h^2)
    ! nodal error of test_lame). BBAR at nu = 0.4999 must be as accurate:
    ! within the larger nu = 0.3 error of the two elements.
    call check('case 2a: ring nu = 0.3, STANDARD is accurate (|error| < 1 %, the mesh error)', abs(error_std3) < 1.0e-2_dp)
    call check('case 2a: ring nu = 0.4999, BBAR error within the nu = 0.3 mesh error', &
               abs(error_bbar5) <= max(abs(error_std3), abs(error_bbar3)))
    ! Locking: the standard element is too stiff (smaller bore displacement)
    ! by far more than the mesh error: at least 10 x.
    call check('case 2a: ring nu = 0.4999, STANDARD locks: too stiff by > 10 x the mesh error', &
               error_std5 < 0.0_dp .and. abs(error_std5) > 10.0_dp*abs(error_std3))

    ! The cantilever block: plane strain, H = 0.01 m, L = 0.1 m, clamped at
    ! z = 0 (FIX BOTTOM RZ), uniform lateral pressure q on the side r = R1.
    ! Bending plus incompressibility is where the standard element locks
    ! worst. Reference: BBAR on 8 x 80 and 16 x 160 meshes, Richardson
    ! extrapolated (O(h^2)); the nu = 0.3 reference likewise with STANDARD.
    ! Timoshenko beam theory (plane strain E' = E/(1 - nu^2), kappa = 5/6)
    ! checks the reference independently.
    do k = 1, 2
      fine(k) = cantilever_tip('BBAR', 0.4999_dp, 8*k)
    end do
    reference5 = fine(2) + (fine(2) - fine(1))/3.0_dp
    do k = 1, 2
      fine(k) = cantilever_tip('STANDARD', 0.3_dp, 8*k)
    end do
    reference3 = fine(2) + (fine(2) - fine(1))/3.0_dp
    beam5 = beam_tip(1.0e3_dp, ring_shear, 0.4999_dp)
    print '(a, 3es13.5)', '  case 2a cantilever tip: reference nu=0.4999, beam theory, reference nu=0.3: ', &
      reference5, beam5, reference3
    print '(a, 2es13.5)', '  case 2a cantilever tip, nu = 0.3 STANDARD on 8 x 80 and 16 x 160: ', fine
    ! Beam theory within 5 %: it ignores the clamp's local effects of order
    ! H/L = 10 % on the root region (the warping of the root section, and the
    ! fixed lateral strain at the clamp, which stiffens a near-incompressible
    ! block); measured: the FE reference is 1.8 % stiffer than beam theory.
    call check_close('case 2a: cantilever converged BBAR reference agrees with Timoshenko beam theory (5 %)', &
                     reference5, beam5, 5.0e-2_dp)
    tip(1) = cantilever_tip('STANDARD', 0.3_dp, 2)/reference3 - 1.0_dp
    tip(2) = cantilever_tip('BBAR', 0.3_dp, 2)/reference3 - 1.0_dp
    tip(3) = cantilever_tip('STANDARD', 0.4999_dp, 2)/reference5 - 1.0_dp
    tip(4) = cantilever_tip('BBAR', 0.4999_dp, 2)/reference5 - 1.0_dp
    print '(a, 4es11.3)', '  case 2a cantilever 2 x 20 tip errors: std 0.3, bbar 0.3, std 0.4999, bbar 0.4999 =', tip
    ! On 2 x 20 elements the bilinear quad also shear-locks in bending (a
    ! mesh error, present at nu = 0.3: -13 % STANDARD, +4 % BBAR); BBAR at
    ! nu = 0.4999 must be within the larger nu = 0.3 error of the two
    ! elements, while STANDARD loses almost all the deflection.
    call check('case 2a: cantilever nu = 0.4999, BBAR error within the nu = 0.3 mesh error', &
               abs(tip(4)) <= max(abs(tip(1)), abs(tip(2))))
    call check('case 2a: cantilever nu = 0.4999, STANDARD locks (tip deflection < 1/2 of the reference)', &
               tip(3) < -0.5_dp)

    ! The deck reader warns for nu = 0.4999 with STANDARD (and names BBAR), not with BBAR.
    call write_deck(folder//'/case2_warn_standard.inp', ring_deck('STANDARD', 0.4999_dp, ring_shear))
    call read_deck(folder//'/case2_warn_standard.inp', deck, error)
    call check('case 2a: the nu = 0.4999 STANDARD deck reads', .not. allocated(error))
    if (allocated(error)) return
    warned = size(deck%warnings) > 0
    call check('case 2a: nu = 0.4999 with STANDARD gives a warning', warned)
    if (warned) call check_text_contains('case 2a: the locking warning names BBAR', deck%warnings(1)%text, 'BBAR')
    call write_deck(folder//'/case2_warn_bbar.inp', ring_deck('BBAR', 0.4999_dp, ring_shear))
    call read_deck(folder//'/case2_warn_bbar.inp', deck, error)
    call check('case 2a: nu = 0.4999 with BBAR reads without a warning', &
               .not. allocated(error) .and. size(deck%warnings) == 0)

    call add_row('2a ring nu=0.4999 NR=NT=8 bore u(a)', 'error STANDARD '//num3(error_std5)//', BBAR '// &
                 num3(error_bbar5)//' (nu=0.3: '//num3(error_std3)//')')
    call add_row('2a cantilever nu=0.4999 2x20 tip', 'error STANDARD '//num3(tip(3))//', BBAR '// &
                 num3(tip(4))//' (nu=0.3: '//num3(tip(1))//')')
  end subroutine case_incompressible_static


  !> Signed relative error of the radial bore displacement, the largest over
  !> the bore nodes, of the ring in a formulation and nu.
  real(dp) function ring_error(formulation, nu) result(worst)
    character(*), intent(in) :: formulation
    real(dp), intent(in) :: nu
    type(deck_t) :: deck
    type(static_solution_t) :: solution
    logical :: ok
    real(dp) :: exact, radius, ur
    integer :: node
    worst = huge(1.0_dp)
    call run_static('case2_ring_'//formulation//'_'//nu_tag(nu), ring_deck(formulation, nu, ring_shear), deck, &
                    solution, ok)
    if (.not. ok) return
    exact = lame_bore(ring_pressure, ring_a, ring_b, ring_shear, bulk_of(ring_shear, nu))
    worst = 0.0_dp
    do node = 1, deck%mesh%nnode
      radius = norm2(deck%mesh%xy(:, node))
      if (abs(radius - ring_a) > 1.0e-9_dp*ring_a) cycle
      ur = dot_product(solution%displacement(:, node), deck%mesh%xy(:, node))/radius
      if (abs(ur/exact - 1.0_dp) > abs(worst)) worst = ur/exact - 1.0_dp
    end do
  end function ring_error

  !> Mean lateral displacement of the free end (z = L) of the cantilever on nr x 10 nr elements.
  real(dp) function cantilever_tip(formulation, nu, nr) result(tip)
    character(*), intent(in) :: formulation
    real(dp), intent(in) :: nu
    integer, intent(in) :: nr
    type(deck_t) :: deck
    type(static_solution_t) :: solution
    logical :: ok
    character(len=16) :: tag
    write(tag, '(i0)') nr
    tip = huge(1.0_dp)
    call run_static('case2_cantilever_'//formulation//'_'//nu_tag(nu)//'_'//trim(tag), [character(len=100) :: &
      'TITLE cantilever block, uniform lateral load', 'ANALYSIS STATIC', 'GEOMETRY PLANESTRAIN', &
      card('FORMULATION '//formulation), elastic_line(2.0_dp*ring_shear*(1.0_dp + nu), nu, 1000.0_dp), &
      card('MESH RECT R0=0.01 R1=0.02 Z0=0 Z1=0.1 NR='//trim(tag)//' NZ='//integer_text(10*nr)), 'FIX BOTTOM RZ', &
      'PRESSURE OUTER P=1e3', 'END'], deck, solution, ok)
    if (.not. ok) return
    tip = sum(solution%displacement(1, :), mask=deck%mesh%xy(2, :) > 0.1_dp - 1.0e-9_dp)/ &
          count(deck%mesh%xy(2, :) > 0.1_dp - 1.0e-9_dp)
  end function cantilever_tip

  !> Timoshenko cantilever under a uniform load q (per unit length and depth),
  !> plane strain: q L^4/(8 E' I) + q L^2/(2 kappa G H), in -r (q pushes into the side r = R1).
  real(dp) function beam_tip(q, g, nu) result(tip)
    real(dp), intent(in) :: q, g, nu
    real(dp), parameter :: length = 0.1_dp, depth = 0.01_dp
    real(dp) :: plane_young
    plane_young = 2.0_dp*g*(1.0_dp + nu)/(1.0_dp - nu**2)
    tip = -(q*length**4/(8.0_dp*plane_young*depth**3/12.0_dp) + q*length**2/(2.0_dp*5.0_dp/6.0_dp*g*depth))
  end function beam_tip

  ! ------------------------------------------------------------------ case 2b

  !> The nu = 0.4999 ring under a suddenly applied internal pressure, DYNAMIC,
  !> BBAR and STANDARD: bounded, finite; the mean bore displacement over the
  !> run (the vibration averages out) shows the locking of STANDARD.
  subroutine case_incompressible_dynamic()
    type(deck_t) :: deck
    type(record_t) :: record
    logical :: ok
    real(dp) :: mean(2), peak(2), ratio(2), static_ratio, exact, window, period
    character(len=8), parameter :: formulations(2) = ['STANDARD', 'BBAR    ']
    integer :: k
    real(dp), allocatable :: bore(:)
    ! The breathing mode of the incompressible ring: u = u(a) a/r, modal mass
    ! rho a^2 ln(b/a) and stiffness 2 G (b^2 - a^2)/b^2 per radian and unit
    ! depth give T = 2 pi sqrt(rho a^2 ln(b/a) b^2/(2 G (b^2 - a^2))) = 1.35 ms.
    period = 2.0_dp*acos(-1.0_dp)*sqrt(1000.0_dp*ring_a**2*log(ring_b/ring_a)*ring_b**2/ &
                                          (2.0_dp*ring_shear*(ring_b**2 - ring_a**2)))
    window = 0.02_dp
    exact = lame_bore(ring_pressure, ring_a, ring_b, ring_shear, bulk_of(ring_shear, 0.4999_dp))
    do k = 1, 2
      call run_dynamic('case2b_'//trim(formulations(k)), [character(len=100) :: &
        ring_deck(trim(formulations(k)), 0.4999_dp, ring_shear, dynamic=.true.)], deck, record, ok)
      if (.not. ok) return
      call check_bounded('case 2b ('//trim(formulations(k))//', nu = 0.4999, dynamic ring)', record, 1.0e-3_dp, &
                         ratio(k))
      bore = history_column(record, 'bore_ur_m')
      mean(k) = sum(bore(2:))/(size(bore) - 1)
      peak(k) = maxval(bore)
    end do
    static_ratio = (1.0_dp + ring_static('STANDARD'))/(1.0_dp + ring_static('BBAR'))
    print '(a, 2es12.4, a, 2es12.4, a, es12.4, a, f7.4)', '  case 2b mean bore u_r STANDARD, BBAR:', mean, &
      '  peak:', peak, '  Lame:', exact, '  T (ms):', 1.0e3_dp*period
    ! The mean over a window W of an oscillation about the static value u_s
    ! with amplitude <= u_s is off by at most u_s T/(pi W) per mode (a
    ! partial period) = 2.2 % for W = 20 ms, T = 1.35 ms; plus the 0.5 % mesh
    ! error of this ring (case 2a: -0.43 % for BBAR).
    call check_close('case 2b: BBAR mean bore u_r over the run equals the Lame displacement (T/(pi W) + mesh)', &
                     mean(2), exact, period/(acos(-1.0_dp)*window) + 5.0e-3_dp)
    call check_close('case 2b: STANDARD/BBAR mean bore u_r equals the static locking ratio (same bound, twice)', &
                     mean(1)/mean(2), static_ratio, 2.0_dp*period/(acos(-1.0_dp)*window))
    call add_row('2b ring nu=0.4999 dynamic, 2000 steps', 'mean bore u_r STANDARD/BBAR '//num3(mean(1)/mean(2))// &
                 ' (static '//num3(static_ratio)//'), BBAR mean/Lame '//num3(mean(2)/exact)//', max E/W '// &
                 num3(maxval(ratio)))
  end subroutine case_incompressible_dynamic

  !> Signed static bore error of the nu = 0.4999 ring (the node on the x axis).
  real(dp) function ring_static(formulation) result(relative)
    character(*), intent(in) :: formulation
    type(deck_t) :: deck
    type(static_solution_t) :: solution
    logical :: ok
    integer :: node
    relative = huge(1.0_dp)
    call run_static('case2b_static_'//formulation, ring_deck(formulation, 0.4999_dp, ring_shear), deck, solution, ok)
    if (.not. ok) return
    node = nearest_node(deck, [ring_a, 0.0_dp])
    relative = solution%displacement(1, node)/lame_bore(ring_pressure, ring_a, ring_b, ring_shear, &
                                                        bulk_of(ring_shear, 0.4999_dp)) - 1.0_dp
  end function ring_static

  ! ------------------------------------------------------------------ case 3

  !> A viscoelastic column, G(t) = G_inf + G1 exp(-beta t), with beta DT from
  !> 1e-12 to 1e6: finite, bounded, dissipation >= 0, and the limits.
  subroutine case_relaxation_times()
    integer, parameter :: nx = 7, nsteps = 200
    real(dp), parameter :: x(nx) = [1.0e-12_dp, 1.0e-9_dp, 1.0e-6_dp, 1.0e-3_dp, 1.0_dp, 1.0e3_dp, 1.0e6_dp]
    real(dp), parameter :: pressure = 1.0e5_dp, dt = 1.0e-4_dp
    type(deck_t) :: deck
    type(record_t) :: record
    logical :: ok
    real(dp) :: bulk, g0, g_inf, g1, ratio, worst_ratio, diff_fast, diff_slow, min_dissipated, scale, diff_first, first_gap
    real(dp), allocatable :: u_g0(:), u_inf(:), u(:)
    integer :: k

    bulk = bulk_of(young1/(2.0_dp*(1.0_dp + poisson1)), poisson1)
    g0 = young1/(2.0_dp*(1.0_dp + poisson1))
    g_inf = 0.3_dp*g0
    g1 = g0 - g_inf
    ! Elastic references with G = G(0) and G = G_inf.
    call run_dynamic('case3_elastic_g0', column_deck('DYNAMIC', [shear_line(g0, bulk)], 40, pressure, 1.4_dp, dt, &
                     nsteps*dt, 1), deck, record, ok)
    if (.not. ok) return
    u_g0 = history_column(record, 'top_uz_m')
    call run_dynamic('case3_elastic_ginf', column_deck('DYNAMIC', [shear_line(g_inf, bulk)], 40, pressure, 1.4_dp, &
                     dt, nsteps*dt, 1), deck, record, ok)
    if (.not. ok) return
    u_inf = history_column(record, 'top_uz_m')

    worst_ratio = 0.0_dp
    min_dissipated = huge(1.0_dp)
    do k = 1, nx
      call run_dynamic('case3_x'//integer_text(k), column_deck('DYNAMIC', [character(len=100) :: &
        card('MATERIAL m VISCOELASTIC K='//exact_text(bulk)//' RHO='//exact_text(density1)), &
        card('PRONY G='//exact_text(g_inf)//' BETA=0'), &
        card('PRONY G='//exact_text(g1)//' BETA='//exact_text(x(k)/dt))], &
        40, pressure, 1.4_dp, dt, nsteps*dt, 1), deck, record, ok)
      if (.not. ok) return
      call check_bounded('case 3 (beta DT = '//num3(x(k))//')', record, 1.0e-3_dp, ratio)
      worst_ratio = max(worst_ratio, ratio)
      min_dissipated = min(min_dissipated, minval(history_column(record, 'dissipated_J'))/ &
                                           maxval(abs(history_column(record, 'external_work_J'))))
      u = history_column(record, 'top_uz_m')
      if (k == 1) then
        scale = maxval(abs(u_g0))
        diff_slow = maxval(abs(u - u_g0))/scale
        ! beta DT = 1e-12: over the run (beta t <= 2e-10) G(t) = G(0) to 1.4e-10
        ! relative, and each step's mu = G_inf + G1 J(theta x) (eq. [21]) differs
        ! from G(0) by G1 theta x/2 = 5e-13 G(0). A relative change of M by
        ! <= 1e-10 shifts the fundamental's phase by <= omega t 1e-10/2
        ! = 26 x 5e-11 ~ 1e-9 of the amplitude. Tolerance 1e-8 (measured 5e-11).
        call check('case 3: beta DT = 1e-12 follows the elastic G = G(0) run (1e-8 of max |u|)', diff_slow <= 1.0e-8_dp, &
                   'max |u - u_G0|/max|u| = '//num3(diff_slow))
      else if (k == nx) then
        scale = maxval(abs(u_inf))
        diff_fast = maxval(abs(u - u_inf))/scale
        diff_first = abs(u(2) - u_inf(2))/scale
        ! beta DT = 1e6: exp(-x) = 0 and J = 1/x = 1e-6 (eq. [22]): the
        ! history of the previous step is gone and each step adds
        ! 2 G1 J de = 2 (G1/beta) de/dt, a dashpot of viscosity G1/beta in
        ! parallel with G_inf. The instantaneous G(0) acts for 1/beta = 1e-6
        ! of a step and never on a finite strain increment, so the run is the
        ! G_inf material from the first step on (in a QUASISTATIC run step 0,
        ! the instantaneous response, would still see G(0); the dynamic run
        ! has no step 0: u = 0 at t = 0). The dashpot damps the fundamental
        ! (omega = 1065 1/s for G_inf) by zeta = (4/3)(G1/beta) omega/(2M) = 2.7e-8,
        ! i.e. zeta omega t = 6e-7 of the amplitude over 20 ms. Tolerance 1e-5
        ! (the higher modes add comparable shares; measured 3.4e-7).
        call check('case 3: beta DT = 1e6 follows the elastic G = G_inf run (1e-5 of max |u|)', diff_fast <= 1.0e-5_dp, &
                   'max |u - u_Ginf|/max|u| = '//num3(diff_fast))
        ! The first step: the same dashpot over one step, ~1e-8; the G(0) run
        ! differs there by first_gap (printed), so 1e-7 tells them apart.
        first_gap = abs(u_g0(2) - u_inf(2))/scale
        call check('case 3: beta DT = 1e6, the first step already follows G_inf (1e-7), not G(0)', &
                   diff_first <= 1.0e-7_dp .and. first_gap > 1.0e-5_dp, &
                   'first step |u - u_Ginf|/max|u| = '//num3(diff_first)//', G(0) run differs by '//num3(first_gap))
      else if (abs(x(k) - 1.0_dp) < 0.5_dp) then
        ! beta DT = 1: relaxation during the run dissipates energy (the dashpot works).
        call check('case 3: beta DT = 1 dissipates (dissipated_J > 1 % of the work at the end)', &
                   history_last(record, 'dissipated_J') > 1.0e-2_dp*history_last(record, 'external_work_J'))
      end if
    end do
    print '(a, 4es11.3)', '  case 3: |u - u_G0| (x = 1e-12), |u - u_Ginf| (x = 1e6), first step, G0-Ginf at step 1:', &
      diff_slow, diff_fast, diff_first, first_gap
    call add_row('3 VISCOELASTIC beta DT = 1e-12 .. 1e6', 'max E/W '//num3(worst_ratio)//'; min dissipated/W '// &
                 num3(min_dissipated)//'; x=1e-12 vs G(0) '//num3(diff_slow)//'; x=1e6 vs G_inf '//num3(diff_fast))
  end subroutine case_relaxation_times

  ! ------------------------------------------------------------------ case 4

  !> 1e5 steps of a 10-element column under constant pressure: bounded,
  !> finite, the balance error bounded and non-positive, no drift: the mean
  !> over two late windows equals the static displacement.
  subroutine case_long_run()
    integer, parameter :: nsteps = 100000, every = 10
    real(dp), parameter :: pressure = 1.0e5_dp
    type(deck_t) :: deck
    type(record_t) :: record
    type(static_solution_t) :: solution
    logical :: ok
    real(dp) :: modulus, period, dt, u_static, ratio, mean_mid, mean_end, window, amplitude, amplitude_mid
    real(dp) :: balance_max, input_max, amplitude_early
    real(dp), allocatable :: u(:), balance(:)
    character(len=100), allocatable :: material(:)
    integer :: n

    material = [elastic_line(young1, poisson1, density1)]
    modulus = constrained_modulus(young1, poisson1)
    period = 4.0_dp*column_length/sqrt(modulus/density1)
    dt = period/50.0_dp
    call run_static('case4_static', column_deck('STATIC', material, 10, pressure), deck, solution, ok)
    if (.not. ok) return
    u_static = top_displacement(deck, solution)
    call run_dynamic('case4_long', column_deck('DYNAMIC', material, 10, pressure, 1.4_dp, dt, nsteps*dt, every), &
                     deck, record, ok)
    if (.not. ok) return
    call check('case 4: the run made 1e5 steps', nint(history_last(record, 'step')) == nsteps)
    call check_bounded('case 4 (1e5 steps)', record, 1.0e-3_dp, ratio)
    u = history_column(record, 'top_uz_m')
    n = size(u)
    ! Two windows of 25,000 steps (500 T1 each): steps 50,000..75,000 and 75,000..100,000.
    window = 25000*dt
    mean_mid = sum(u(n/2:3*n/4 - 1))/size(u(n/2:3*n/4 - 1))
    mean_end = sum(u(3*n/4:n - 1))/size(u(3*n/4:n - 1))
    amplitude_mid = maxval(abs(u(n/2:3*n/4 - 1) - u_static))
    amplitude = maxval(abs(u(3*n/4:n - 1) - u_static))
    ! An oscillation of amplitude A about u_static has a window mean off by at
    ! most A T/(pi W) (a partial period); by now only the fundamental is left
    ! (the higher modes are damped out), T = T1 within 1 % at dt = T1/50:
    ! tolerance 2 A T1/(pi W) = 2 A/(500 pi) with each window's own A.
    print '(a, 4es12.4)', '  case 4: static, mean steps 5e4-7.5e4, mean 7.5e4-1e5, last amplitude:', u_static, &
      mean_mid, mean_end, amplitude
    call check_close('case 4: mean top u_z over steps 50,000-75,000 = static (A T/(pi W) bound)', mean_mid, u_static, &
                     0.0_dp, 2.0_dp*amplitude_mid*period/(acos(-1.0_dp)*window))
    call check_close('case 4: mean top u_z over steps 75,000-100,000 = static (no drift)', mean_end, u_static, &
                     0.0_dp, 2.0_dp*amplitude*period/(acos(-1.0_dp)*window))
    ! Balance error = kinetic + internal work - input: <= 0 (the integrator
    ! only removes energy; round-off 1e-9 of the input as for dissipated_J)
    ! and bounded by the input (it cannot remove more than was put in).
    balance = history_column(record, 'balance_error_J')
    input_max = maxval(abs(history_column(record, 'external_work_J')))
    balance_max = maxval(balance)
    call check('case 4: balance error <= round-off at every row (non-positive)', balance_max <= 1.0e-9_dp*input_max)
    call check('case 4: |balance error| <= the input energy at every row (bounded)', &
               all(abs(balance) <= input_max))
    ! (The balance is not monotone row to row: the physical energy of a
    ! Wilson-theta solution oscillates within a step's O((omega dt)^2); the
    ! largest rise between rows is measured as 1e-3 of W.) No growth: the
    ! vibration about the static state decays, the amplitude over the last
    ! quarter is below the one over the second quarter.
    amplitude_early = maxval(abs(u(n/4:n/2 - 1) - u_static))
    print '(a, 2es12.4)', '  case 4: vibration amplitude over the 2nd and 4th quarters:', amplitude_early, amplitude
    call check('case 4: the vibration amplitude does not grow (4th quarter <= 2nd quarter)', amplitude <= amplitude_early)
    call add_row('4 1e5 steps, dt = T1/50', 'max E/W '//num3(ratio)//'; mean u end/static - 1 '// &
                 num3(mean_end/u_static - 1.0_dp)//'; balance error in ['//num3(minval(balance)/input_max)//', '// &
                 num3(balance_max/input_max)//'] W')
  end subroutine case_long_run

  ! ------------------------------------------------------------------ case 5

  !> A very soft column, E = 100 Pa under p = 1e5 Pa (linear strain ~ 900):
  !> finite, bounded, and the linear answer: the exact scaling of the Table 1
  !> column's run (u x E1/E at time x sqrt(E1/E)) and the static solution.
  subroutine case_soft_material()
    real(dp), parameter :: soft = 100.0_dp, pressure = 1.0e5_dp, dt = 1.0e-4_dp
    integer, parameter :: nsteps = 400
    type(deck_t) :: deck
    type(record_t) :: record
    type(static_solution_t) :: solution
    logical :: ok
    real(dp) :: factor, ratio, u_static, scaling_error
    real(dp), allocatable :: u_stiff(:), u_soft(:)

    factor = young1/soft
    call run_static('case5_static', column_deck('STATIC', [elastic_line(soft, poisson1, density1)], 40, pressure), &
                    deck, solution, ok)
    if (.not. ok) return
    u_static = top_displacement(deck, solution)
    call check_close('case 5: soft static column top u_z = -p L/M (175 m: linear, round-off 1e-10)', u_static, &
                     -pressure*column_length/constrained_modulus(soft, poisson1), 1.0e-10_dp)
    call run_dynamic('case5_stiff', column_deck('DYNAMIC', [elastic_line(young1, poisson1, density1)], 40, pressure, &
                     1.4_dp, dt, nsteps*dt, 1), deck, record, ok)
    if (.not. ok) return
    u_stiff = history_column(record, 'top_uz_m')
    call run_dynamic('case5_soft', column_deck('DYNAMIC', [elastic_line(soft, poisson1, density1)], 40, pressure, &
                     1.4_dp, dt*sqrt(factor), nsteps*dt*sqrt(factor), 1), deck, record, ok)
    if (.not. ok) return
    call check_bounded('case 5 (E = 100 Pa, p = 1e5 Pa)', record, 1.0e-3_dp, ratio)
    u_soft = history_column(record, 'top_uz_m')
    ! M u'' + S u = R with S -> S/f and dt -> dt sqrt(f) is solved by u -> f u:
    ! every Wilson-theta operation scales exactly (S~ = S + 6 M/(theta dt)^2 -> S~/f,
    ! the right side is unchanged), so the runs agree to round-off, ~1e-13 of
    ! max |u|; tolerance 1e-10.
    scaling_error = maxval(abs(u_soft - factor*u_stiff))/maxval(abs(u_soft))
    call check('case 5: the soft run is the stiff run scaled by E1/E (linear, 1e-10 of max |u|)', &
               size(u_soft) == size(u_stiff) .and. scaling_error <= 1.0e-10_dp, 'error '//num3(scaling_error))
    print '(a, 2es12.4)', '  case 5: soft static top u_z (m), soft/stiff scaling error:', u_static, scaling_error
    call add_row('5 E=100 Pa under p=1e5 Pa', 'static u_z '//num3(u_static)//' m = -p L/M; max E/W '//num3(ratio)// &
                 '; soft run = stiff run x E1/E to '//num3(scaling_error))
  end subroutine case_soft_material

  ! ------------------------------------------------------------------ case 6

  !> theta = 1.0: a warning when read, detected as unstable at a large DT
  !> (no case folder written), fine at a small DT; theta = 0.9 rejected.
  subroutine case_conditional_theta()
    real(dp), parameter :: pressure = 1.0e5_dp
    type(deck_t) :: deck
    type(record_t) :: record
    type(error_t), allocatable :: error
    logical :: ok, warned
    real(dp) :: dt_crit, ratio, modulus, omega_max
    character(len=100), allocatable :: material(:), lines(:)
    character(:), allocatable :: out_root, text
    integer :: k, wilson_line

    material = [elastic_line(young1, poisson1, density1)]
    modulus = constrained_modulus(young1, poisson1)
    dt_crit = column_width/sqrt(modulus/density1)

    lines = column_deck('DYNAMIC', material, 40, pressure, 1.0_dp, 1000.0_dp*dt_crit, 100*1000.0_dp*dt_crit, 1)
    call write_deck(folder//'/case6_theta1_large.inp', lines)
    call read_deck(folder//'/case6_theta1_large.inp', deck, error)
    call check('case 6: WILSON THETA=1.0 reads', .not. allocated(error))
    if (allocated(error)) return
    warned = size(deck%warnings) > 0
    call check('case 6: THETA=1.0 gives a warning when read', warned)
    if (warned) call check_text_contains('case 6: the THETA warning mentions 1.37', deck%warnings(1)%text, '1.37')
    call solve_dynamic(deck, record, error)
    call check('case 6: THETA=1.0 with DT = 1000 dt_crit: solve_dynamic returns an error', allocated(error))
    if (allocated(error)) then
      text = error_text(error)
      print '(a)', '  case 6 error: '//text
      call check_text_contains('case 6: the error says "unstable"', text, 'unstable')
      call check_text_contains('case 6: the error names THETA', text, 'THETA')
    end if
    out_root = folder//'/out'
    call execute_command_line('rm -rf '//out_root)
    call execute_command_line('mkdir -p '//out_root)
    call run_deck(folder//'/case6_theta1_large.inp', out_root, record, error)
    call check('case 6: run_deck returns the error', allocated(error))
    call check('case 6: run_deck wrote no case folder', .not. directory_exists(out_root//'/case6_theta1_large'))

    ! A small step: DT = 0.5 dt_crit. The chain's omega_max = 2 c_p/h (h = 0.005)
    ! gives dt/T_min = 0.5 dt_crit omega_max/(2 pi) = 0.16, well below 0.55.
    omega_max = 2.0_dp*sqrt(modulus/density1)/(column_length/40)
    call run_dynamic('case6_theta1_small', column_deck('DYNAMIC', material, 40, pressure, 1.0_dp, 0.5_dp*dt_crit, &
                     2000*0.5_dp*dt_crit, 1), deck, record, ok)
    if (ok) then
      ! theta = 1 is the undamped linear-acceleration method: the physical
      ! energy is not dissipated, only oscillates by O((omega dt)^2) in the
      ! modes; started from rest the measured ratio stays below 1 (0.9999),
      ! so the common tolerance 1e-3 applies.
      call check_bounded('case 6 (THETA = 1.0, DT = 0.5 dt_crit, dt/T_min = '// &
                         num3(0.5_dp*dt_crit*omega_max/(2.0_dp*acos(-1.0_dp)))//')', record, 1.0e-3_dp, ratio)
    end if

    ! THETA = 0.9 is rejected, naming the line and THETA.
    lines = column_deck('DYNAMIC', material, 40, pressure, 0.9_dp, dt_crit, 10*dt_crit, 1)
    wilson_line = 0
    do k = 1, size(lines)
      if (lines(k)(1:6) == 'WILSON') wilson_line = k
    end do
    call write_deck(folder//'/case6_theta09.inp', lines)
    call read_deck(folder//'/case6_theta09.inp', deck, error)
    call check('case 6: THETA=0.9 is rejected by read_deck', allocated(error))
    if (allocated(error)) then
      text = error_text(error)
      call check_text_contains('case 6: the THETA=0.9 error names the line', text, 'case6_theta09.inp:'// &
                               integer_text(wilson_line)//':')
      call check_text_contains('case 6: the THETA=0.9 error names THETA', text, 'THETA')
    end if
    call add_row('6 THETA=1.0 DT=1000 dt_crit', 'error "unstable ... THETA", no case folder; '// &
                 'DT=0.5 dt_crit: max E/W '//num3(ratio)//'; THETA=0.9 rejected')
  end subroutine case_conditional_theta

  ! ------------------------------------------------------------------ case 7

  !> theta = 1.0 in an impact (the Table 1 sphere, level 1, SLIP with release,
  !> DT = 0.2 ms, 20 x the paper's step): the integration diverges. It once
  !> exited 0 with kinetic energies of 1e15 J and a plausible alpha_max_mm,
  !> because the instability bound counted the gross work of the plate
  !> reactions, which grow with the blow-up. A rigid fixed plate does no
  !> positive work on the body: the bound is now the initial kinetic energy
  !> plus the positive work of loads, gravity and prescribed motions, and the
  !> run must stop with a located error (the TIME card) for every stop
  !> criterion, leaving no output. The same deck at THETA = 1.4 is stable:
  !> it must run, with kinetic + strain energy at most the work put in times
  !> 1 + 5e-2. DT = 0.2 ms leaves only about 16 steps in the contact (Hertz
  !> contact time 3.2 ms), so the trapezoidal work of the contact forces is
  !> good to a few percent, not 1e-3 (measured: max E/W = 1.016); 5 % bounds
  !> that and is far below both the guard's 100 x and the factor 1900 by which
  !> THETA = 1.0 raises the energy in three steps.
  subroutine case_diverging_impact()
    character(len=100), allocatable :: lines(:)
    character(len=14), parameter :: stops(3) = ['MAXDEFORMATION', 'SEPARATION    ', 'TEND          ']
    type(deck_t) :: deck
    type(record_t) :: record
    type(error_t), allocatable :: error
    character(:), allocatable :: out_root, text, name
    real(dp) :: ratio
    logical :: ok
    integer :: k, time_line
    out_root = folder//'/out7'
    call execute_command_line('rm -rf '//out_root//' && mkdir -p '//out_root)
    do k = 1, size(stops)
      name = 'case7_theta1_'//trim(stops(k))
      lines = impact_deck('1.0', trim(stops(k)))
      time_line = findloc(lines(:)(1:4) == 'TIME', .true., dim=1)
      call write_deck(folder//'/'//name//'.inp', lines)
      call run_deck(folder//'/'//name//'.inp', out_root, record, error)
      call check('case 7: THETA=1.0, STOP AT='//trim(stops(k))//': the diverging impact stops with an error', &
                 allocated(error))
      if (allocated(error)) then
        text = error_text(error)
        if (k == 1) print '(a)', '  case 7 error: '//text
        call check_text_contains('case 7 ('//trim(stops(k))//'): the error is located at the TIME card', text, &
                                 name//'.inp:'//integer_text(time_line)//': TIME: ')
        call check_text_contains('case 7 ('//trim(stops(k))//'): the error says "unstable"', text, 'unstable')
        deallocate(error)
      end if
      call check('case 7 ('//trim(stops(k))//'): no case folder written', &
                 .not. directory_exists(out_root//'/'//name))
    end do
    call run_dynamic('case7_theta14', impact_deck('1.4', 'SEPARATION'), deck, record, ok)
    if (ok) call check_bounded('case 7 (THETA = 1.4, DT = 0.2 ms)', record, 5.0e-2_dp, ratio)
    call add_row('7 impact THETA=1.0 DT=0.2 ms', 'error "unstable" at TIME for 3 stop criteria, no output; '// &
                 'THETA=1.4: max E/W '//num3(ratio))
  end subroutine case_diverging_impact

  !> The Table 1 sphere (level 1) dropped on a SLIP plate with release, DT = 0.2 ms.
  function impact_deck(theta, stop_at) result(lines)
    character(*), intent(in) :: theta, stop_at
    character(len=100), allocatable :: lines(:)
    lines = [character(len=100) :: 'TITLE diverging impact (theta = '//theta//')', 'ANALYSIS DYNAMIC', &
             'MATERIAL apple ELASTIC E=18.11e6 NU=0.219 RHO=756.85', 'MESH SPHERE R=0.0366 LEVEL=1', &
             'INITIAL VZ=-0.9982 AZ=-9.8', 'GRAVITY G=9.8', 'WILSON THETA='//theta, 'TIME DT=2e-4 TEND=4e-3', &
             'PLATE Z=0 SLIP RELEASE=YES', 'STOP AT='//stop_at, 'END']
  end function impact_deck

  ! ---------------------------------------------------------------- helpers

  !> K + 4G/3 of (E, nu): the modulus of the laterally confined column.
  pure real(dp) function constrained_modulus(young, poisson)
    real(dp), intent(in) :: young, poisson
    constrained_modulus = young*(1.0_dp - poisson)/((1.0_dp + poisson)*(1.0_dp - 2.0_dp*poisson))
  end function constrained_modulus

  !> K of (G, nu).
  pure real(dp) function bulk_of(shear, poisson)
    real(dp), intent(in) :: shear, poisson
    bulk_of = 2.0_dp*shear*(1.0_dp + poisson)/(3.0_dp*(1.0_dp - 2.0_dp*poisson))
  end function bulk_of

  !> Plane-strain Lame bore displacement u(a) = p a/(b^2 - a^2) [a^2/(2(K + G/3)) + b^2/(2G)].
  pure real(dp) function lame_bore(p, a, b, shear, bulk)
    real(dp), intent(in) :: p, a, b, shear, bulk
    lame_bore = p*a/(b**2 - a**2)*(a**2/(2.0_dp*(bulk + shear/3.0_dp)) + b**2/(2.0_dp*shear))
  end function lame_bore

  !> The quarter ring a = 0.01, b = 0.02 m (NR = NT = 8), plane strain, under
  !> p = 1e4 Pa inside; G = shear, the given nu, rho = 1000. Dynamic: 2000
  !> steps of 1e-5 s (the breathing period is 1.35 ms), probe at the bore.
  function ring_deck(formulation, nu, shear, dynamic) result(lines)
    character(*), intent(in) :: formulation
    real(dp), intent(in) :: nu, shear
    logical, intent(in), optional :: dynamic
    character(len=100), allocatable :: lines(:)
    logical :: is_dynamic
    is_dynamic = .false.
    if (present(dynamic)) is_dynamic = dynamic
    lines = [character(len=100) :: 'TITLE thick cylinder, internal pressure', &
             card('ANALYSIS '//trim(merge('DYNAMIC', 'STATIC ', is_dynamic))), 'GEOMETRY PLANESTRAIN', &
             card('FORMULATION '//formulation), elastic_line(2.0_dp*shear*(1.0_dp + nu), nu, 1000.0_dp), &
             'MESH RING R0=0.01 R1=0.02 NR=8 NT=8', 'FIX AXIS R', 'FIX BOTTOM Z', 'PRESSURE INNER P=1e4', &
             'PROBE bore R=0.01 Z=0']
    if (is_dynamic) lines = [character(len=100) :: lines, 'TIME DT=1e-5 TEND=0.02', 'INITIAL AZ=0 AR=0']
    lines = [character(len=100) :: lines, 'END']
  end function ring_deck

  function nu_tag(nu) result(tag)
    real(dp), intent(in) :: nu
    character(:), allocatable :: tag
    tag = trim(merge('nu4999', 'nu3   ', nu > 0.4_dp))
  end function nu_tag


  !> Three significant digits, for names and the table.
  function num3(x) result(text)
    real(dp), intent(in) :: x
    character(:), allocatable :: text
    character(len=32) :: buffer
    write(buffer, '(es10.3)') x
    text = trim(adjustl(buffer))
  end function num3


  !> A deck line of fixed length 100 (array constructors of
  !> character(len=100) get elements of one length: gfortran 12 overruns the
  !> buffer of a deferred-length concatenation inside such a constructor).
  pure function card(text) result(line)
    character(*), intent(in) :: text
    character(len=100) :: line
    line = text
  end function card

  function elastic_line(young, poisson, density) result(line)
    real(dp), intent(in) :: young, poisson, density
    character(len=100) :: line
    line = 'MATERIAL m ELASTIC E='//exact_text(young)//' NU='//exact_text(poisson)//' RHO='//exact_text(density)
  end function elastic_line

  function shear_line(shear, bulk) result(line)
    real(dp), intent(in) :: shear, bulk
    character(len=100) :: line
    line = 'MATERIAL m ELASTIC G='//exact_text(shear)//' K='//exact_text(bulk)//' RHO='//exact_text(density1)
  end function shear_line

  !> The column deck: plane strain, MESH RECT 0.0025 x 0.2 m with NZ elements,
  !> u_r fixed on both sides (1-D, confined), u_z fixed at the bottom, a
  !> pressure p on the top from t = 0. STATIC decks get no time cards;
  !> DYNAMIC decks start from rest (INITIAL AZ=0 AR=0) unless from_rest = .false.
  function column_deck(analysis, material, nz, pressure, theta, dt, tend, every, from_rest) result(lines)
    character(*), intent(in) :: analysis
    character(len=100), intent(in) :: material(:)
    integer, intent(in) :: nz
    real(dp), intent(in) :: pressure
    real(dp), intent(in), optional :: theta, dt, tend
    integer, intent(in), optional :: every
    logical, intent(in), optional :: from_rest
    character(len=100), allocatable :: lines(:)
    lines = [character(len=100) :: 'TITLE column under a suddenly applied pressure', card('ANALYSIS '//analysis), &
             'GEOMETRY PLANESTRAIN', material, card('MESH RECT R0=0.01 R1=0.0125 Z0=0 Z1=0.2 NR=1 NZ='//integer_text(nz)), &
             'FIX INNER R', 'FIX OUTER R', 'FIX BOTTOM Z', card('PRESSURE TOP P='//exact_text(pressure)), &
             'PROBE top R=0.01 Z=0.2']
    if (analysis == 'DYNAMIC') then
      lines = [character(len=100) :: lines, card('WILSON THETA='//exact_text(theta)), &
               card('TIME DT='//exact_text(dt)//' TEND='//exact_text(tend)), card('OUTPUT EVERY='//integer_text(every))]
    end if
    if (analysis == 'DYNAMIC') then
      if (.not. present(from_rest)) then
        lines = [character(len=100) :: lines, 'INITIAL AZ=0 AR=0']
      else if (from_rest) then
        lines = [character(len=100) :: lines, 'INITIAL AZ=0 AR=0']
      end if
    end if
    lines = [character(len=100) :: lines, 'END']
  end function column_deck

  !> Write, read and run a dynamic deck; check that it runs.
  subroutine run_dynamic(name, lines, deck, record, ok)
    character(*), intent(in) :: name
    character(len=100), intent(in) :: lines(:)
    type(deck_t), intent(out) :: deck
    type(record_t), intent(out) :: record
    logical, intent(out) :: ok
    type(error_t), allocatable :: error
    call write_deck(folder//'/'//name//'.inp', lines)
    call read_deck(folder//'/'//name//'.inp', deck, error)
    if (.not. allocated(error)) call solve_dynamic(deck, record, error)
    ok = .not. allocated(error)
    if (ok) then
      call check(name//': reads and runs', ok)
    else
      call check(name//': reads and runs', ok, error_text(error))
    end if
  end subroutine run_dynamic

  !> Write, read and solve a static deck; check that it solves.
  subroutine run_static(name, lines, deck, solution, ok)
    character(*), intent(in) :: name
    character(len=100), intent(in) :: lines(:)
    type(deck_t), intent(out) :: deck
    type(static_solution_t), intent(out) :: solution
    logical, intent(out) :: ok
    type(error_t), allocatable :: error
    call write_deck(folder//'/'//name//'.inp', lines)
    call read_deck(folder//'/'//name//'.inp', deck, error)
    if (.not. allocated(error)) call solve_static(deck%mesh, deck%materials, deck%settings, deck%loads, deck%source, &
      solution, error)
    ok = .not. allocated(error)
    if (ok) then
      call check(name//': reads and solves', ok)
    else
      call check(name//': reads and solves', ok, error_text(error))
    end if
  end subroutine run_static

  !> Index of the node nearest a point.
  integer function nearest_node(deck, point)
    type(deck_t), intent(in) :: deck
    real(dp), intent(in) :: point(2)
    nearest_node = minloc(norm2(deck%mesh%xy - spread(point, 2, deck%mesh%nnode), dim=1), dim=1)
  end function nearest_node

  !> u_z of the column's top node at r = 0.01.
  real(dp) function top_displacement(deck, solution)
    type(deck_t), intent(in) :: deck
    type(static_solution_t), intent(in) :: solution
    top_displacement = solution%displacement(2, nearest_node(deck, [0.01_dp, column_length]))
  end function top_displacement

  !> Every history value and snapshot field is finite; kinetic + strain <=
  !> (work on the body + initial kinetic) (1 + tolerance) at every row
  !> (+ 1e-12 of the input for round-off at the rows where both are ~0);
  !> dissipated_J >= -1e-9 of the input. `ratio`: the largest
  !> (kinetic + strain)/(work + initial kinetic) over the rows.
  subroutine check_bounded(name, record, tolerance, ratio)
    character(*), intent(in) :: name
    type(record_t), intent(in) :: record
    real(dp), intent(in) :: tolerance
    real(dp), intent(out) :: ratio
    real(dp), allocatable :: stored(:), input(:), dissipated(:)
    logical :: finite
    integer :: s
    finite = all(ieee_is_finite(record%history(:, 1:record%nrow)))
    do s = 1, size(record%snapshots)
      associate (snapshot => record%snapshots(s))
      finite = finite .and. all(ieee_is_finite(snapshot%displacement)) .and. all(ieee_is_finite(snapshot%velocity)) &
               .and. all(ieee_is_finite(snapshot%acceleration)) .and. all(ieee_is_finite(snapshot%stress)) &
               .and. all(ieee_is_finite(snapshot%stress_gauss)) .and. all(ieee_is_finite(snapshot%max_shear)) &
               .and. all(ieee_is_finite(snapshot%von_mises))
      end associate
    end do
    call check(name//': every history value and snapshot field is finite', finite .and. size(record%snapshots) >= 2)
    stored = history_column(record, 'kinetic_J') + history_column(record, 'strain_J')
    input = history_column(record, 'external_work_J') + history_column(record, 'gravity_work_J') + &
            record%history(history_index(record, 'kinetic_J'), 1)
    dissipated = history_column(record, 'dissipated_J')
    ratio = maxval(stored/max(input, tiny(1.0_dp)), mask=input > 1.0e-12_dp*maxval(abs(input)))
    print '(a, es12.4, a, es12.4)', '  '//name//': max (kinetic + strain)/input = ', ratio, &
      ', min dissipated/max input = ', minval(dissipated)/maxval(abs(input))
    call check(name//': kinetic + strain <= (work + initial kinetic) (1 + '//num3(tolerance)//') at every row', &
               all(stored <= input*(1.0_dp + tolerance) + 1.0e-12_dp*maxval(abs(input))))
    call check(name//': dissipated_J >= -1e-9 of the input energy', all(dissipated >= -1.0e-9_dp*maxval(abs(input))))
  end subroutine check_bounded

  !> A row of the closing table: "case | what it showed".
  subroutine add_row(label, text)
    character(*), intent(in) :: label, text
    character(len=44) :: padded
    padded = label
    table_rows = table_rows + 1
    table(table_rows) = padded//' | '//text
  end subroutine add_row
end program test_stability
