!> Verification of the Wilson-theta dynamics (eqs. [25]-[42]) against the
!> 1-D wave in an elastic half-space under a suddenly applied surface
!> traction p0 (inputs/halfspace_wave.inp: a laterally fixed column, so
!> the wave travels at the constrained speed c = sqrt(M_c/rho) = 100 m/s).
!> Exact solution at depth d below the loaded top:
!>   sigma_z = -p0 H(t - d/c), v_z = -p0/(rho c) behind the front,
!>   u_top = -p0 t/(rho c), kinetic = strain energy = W/2 (W = work of p0).
!> The deck itself is checked against that (arrival of the front, plateau,
!> top displacement, momentum, energy). The front is then measured for
!> several time steps and theta = 1.4, and theta = 1.0 at a small step,
!> against an independent reference: the semi-discrete column (the same
!> lumped-mass chain, integrated in time by RK4 at a tiny step), whose
!> front is the Airy front of the dispersive lattice. What Wilson-theta adds
!> to it (wider front, smaller overshoot, dissipated energy) is printed as
!> a table for doc/verification.md and checked for the expected trends.
program test_wave
  use visco2d_kinds, only: dp
  use visco2d_error, only: error_t, error_text
  use visco2d_strings, only: table_real, short_real
  use visco2d_deck, only: deck_t, read_deck
  use visco2d_dynamic, only: solve_dynamic
  use visco2d_record, only: record_t
  use visco2d_testing, only: check, check_close, test_summary, write_deck, history_column, history_last, read_lines
  implicit none

  character(*), parameter :: deck_file = 'inputs/halfspace_wave.inp'
  character(*), parameter :: folder = 'build/test-tmp/test_wave'
  ! The deck's model (the test checks that the deck says so).
  real(dp), parameter :: p0 = 1.0e5_dp                  !< surface traction, Pa
  real(dp), parameter :: rho = 1000.0_dp                !< kg/m^3
  real(dp), parameter :: modulus = 1.0e7_dp             !< constrained modulus M_c = K + 4G/3, Pa
  real(dp), parameter :: speed = 100.0_dp               !< c = sqrt(M_c/rho), m/s
  real(dp), parameter :: velocity = p0/(rho*speed)      !< particle speed behind the front, m/s
  real(dp), parameter :: height = 1.0_dp                !< column depth, m
  real(dp), parameter :: width = 2.5e-3_dp              !< column width (plane strain, per m thickness), m
  real(dp), parameter :: dz = 2.5e-3_dp                 !< element size, m (NZ = 400)
  integer, parameter :: nz = 400
  real(dp), parameter :: t_end = 9.0e-3_dp              !< s: the front is 0.1 m above the bottom
  character(len=4), parameter :: probe_names(3) = ['d025', 'd050', 'd075']
  real(dp), parameter :: depths(3) = [0.25_dp, 0.5_dp, 0.75_dp]
  ! The Airy front: sigma_z/(-p0) = int_xi^inf Ai(s) ds (mpmath, 30 digits) is
  ! 0.1, 0.5, 0.9 at these xi and peaks at the first zero of Ai.
  real(dp), parameter :: airy_xi10 = 0.978224616212_dp, airy_xi50 = -0.409602956933_dp, &
                         airy_xi90 = -1.189418465783_dp, airy_peak = 1.274352059138_dp

  !> What one probe's sigma_z history shows of the front.
  type :: front_t
    real(dp) :: arrival = huge(1.0_dp)    !< s, sigma_z first reaches -p0/2 (interpolated)
    real(dp) :: rise = huge(1.0_dp)       !< s, from -0.1 p0 to -0.9 p0
    real(dp) :: overshoot = huge(1.0_dp)  !< max |sigma_z|/p0 - 1
  end type front_t

  !> One Wilson-theta run of the column, measured.
  type :: run_t
    real(dp) :: theta = 0.0_dp, courant = 0.0_dp, dt = 0.0_dp
    type(front_t) :: front(3)
    real(dp) :: stress_error(3) = huge(1.0_dp)    !< window mean of sigma_z/(-p0) - 1
    real(dp) :: velocity_error(3) = huge(1.0_dp)  !< window mean of v_z/(-v) - 1
    real(dp) :: work = 0.0_dp, balance = 0.0_dp   !< J per m at t_end
    logical :: ok = .false.
  end type run_t

  type(front_t) :: reference(3)
  character(:), allocatable :: lines(:)   ! the archived deck
  logical :: found

  call execute_command_line('mkdir -p '//folder)
  call read_lines(deck_file, lines, found)
  if (.not. found) call check('read_'//deck_file, .false., 'cannot open the file')
  call semi_discrete_reference(reference)
  call test_deck()
  call test_time_steps()
  call test_summary('test_wave')

contains

  !> The archived deck: its model, then every quantity with an exact answer.
  subroutine test_deck()
    type(deck_t) :: deck
    type(record_t) :: record
    type(error_t), allocatable :: error
    type(run_t) :: run
    real(dp), allocatable :: t(:), top(:), vcm(:), ucm(:), sr(:)
    real(dp) :: dt, depth, kinetic, strain, worst, tolerance
    integer :: p, last
    character(len=8) :: name

    ! The archived deck writes every 10th step (a small reference file); the
    ! arrival and rise measurements here need every step.
    call write_deck(folder//'/wave_deck.inp', every_step(lines))
    call read_deck(folder//'/wave_deck.inp', deck, error)
    if (allocated(error)) then
      call check('wave_deck_reads', .false., error_text(error)); return
    end if
    call check('wave_deck_reads', .true.)
    associate (material => deck%materials(1))
    call check_close('wave_deck_constrained_modulus', material%bulk + 4.0_dp/3.0_dp*material%shear, modulus, 1.0e-12_dp)
    call check_close('wave_deck_density', material%density, rho, 1.0e-15_dp)
    end associate
    call check('wave_deck_mesh', deck%mesh%nelem == nz .and. size(deck%stages) == 1)
    call check_close('wave_deck_t_end', deck%stages(1)%end_time, t_end, 1.0e-15_dp)
    call check('wave_deck_probes', size(deck%probes) == 4)
    call check('wave_deck_probe_top', deck%probes(1)%name == 'top' .and. &
               abs(deck%mesh%xy(2, deck%probes(1)%node) - height) < 1.0e-12_dp)
    do p = 1, 3
      call check('wave_deck_probe_'//probe_names(p), deck%probes(p + 1)%name == probe_names(p) .and. &
                 abs(height - deck%mesh%xy(2, deck%probes(p + 1)%node) - depths(p)) < 1.0e-12_dp)
    end do
    dt = deck%stages(1)%dt

    call solve_dynamic(deck, record, error)
    if (allocated(error)) then
      call check('wave_deck_solves', .false., error_text(error)); return
    end if
    call check('wave_deck_solves', .true.)
    ! Plateau windows from 1 ms behind the front to the end: the ringing there
    ! is below 8 % (peak) with periods of ~0.1 ms, so a mean over >= 0.5 ms
    ! is within a few 0.1 % of the plateau: 1 % tolerance.
    call measure_run(deck, record, 1.0e-3_dp, run)
    print '(a)', '# the deck (theta = 1.4, C = c dt/dz = '//short_real(speed*dt/dz)//'), at the probes:'
    print '(a)', '#   depth  arrival-d/c (dz/c)  rise (elements)  overshoot   plateau sigma_z err   v_z err'
    do p = 1, 3
      print '(a, f6.2, f14.3, f17.2, f14.4, es19.2, es12.2)', '#  ', depths(p), &
        (run%front(p)%arrival - depths(p)/speed)*speed/dz, run%front(p)%rise*speed/dz, run%front(p)%overshoot, &
        run%stress_error(p), run%velocity_error(p)
    end do
    do p = 1, 3
      name = probe_names(p)
      depth = depths(p)
      ! Arrival of the half level vs d/c: the dispersive lattice turns the
      ! step into an Airy front whose half level lags by 0.41 L/c,
      ! L = dz (d/(8 dz))^(1/3) <= 3.4 dz here, i.e. <= 1.4 dz/c; Wilson-theta
      ! adds less than one step (test_time_steps). Tolerance 2 dz/c + 2 dt.
      tolerance = 2.0_dp*dz/speed + 2.0_dp*dt
      call check('wave_arrival_'//trim(name), abs(run%front(p)%arrival - depth/speed) <= tolerance, &
                 'arrival '//table_real(run%front(p)%arrival)//' s, d/c = '//table_real(depth/speed)//' s, tolerance '// &
                 table_real(tolerance))
      call check('wave_plateau_stress_'//trim(name), abs(run%stress_error(p)) <= 1.0e-2_dp, &
                 'relative error '//table_real(run%stress_error(p)))
      call check('wave_plateau_velocity_'//trim(name), abs(run%velocity_error(p)) <= 1.0e-2_dp, &
                 'relative error '//table_real(run%velocity_error(p)))
    end do
    ! The 1-D state: sigma_r = nu/(1 - nu) sigma_z = -p0/3 behind the front (same window, same 1 %).
    t = history_column(record, 't_s')
    sr = history_column(record, 'd025_sr_Pa')
    call check_close('wave_plateau_lateral_stress_d025', window_mean(t, sr, depths(1)/speed + 1.0e-3_dp), &
                     -p0/3.0_dp, 1.0e-2_dp)

    ! The top moves at the constant speed v from t = 0. The discrete top
    ! node (mass rho dz/2 per area, pushed by p0) needs dz/(2c) to get up to
    ! speed, losing v dz/(4c), and the first step cannot follow the jump in
    ! velocity (at most v dt); afterwards momentum conservation makes it
    ! catch up. Bound over the whole history: v (dz/(4c) + dt).
    top = history_column(record, 'top_uz_m')
    worst = maxval(abs(top + velocity*t))
    tolerance = velocity*(dz/(4.0_dp*speed) + dt)
    print '(a, es10.3, a, es10.3, a)', '# top displacement: worst |u + v t| = ', worst, ' m (bound ', tolerance, ' m)'
    call check('wave_top_displacement_history', worst <= tolerance, 'worst '//table_real(worst)//' m')
    last = size(t)
    call check_close('wave_top_displacement_end', top(last), -velocity*t_end, dt/t_end)

    ! Momentum: the load impulse p0 b t all goes into the column (the bottom
    ! reaction ahead of the front is < 1e-10 of the load); Wilson-theta keeps
    ! sum M a = sum R exactly (eqs. [37]-[42] interpolate the stage
    ! equilibrium linearly). Round-off: 1e-9.
    vcm = history_column(record, 'vz_cm_m_s')
    ucm = history_column(record, 'uz_cm_m')
    worst = maxval(abs(vcm + p0*t/(rho*height)))/(p0*t_end/(rho*height))
    call check('wave_momentum_velocity', worst <= 1.0e-9_dp, 'worst relative error '//table_real(worst))
    worst = maxval(abs(ucm + 0.5_dp*p0*t**2/(rho*height)))/(0.5_dp*p0*t_end**2/(rho*height))
    call check('wave_momentum_displacement', worst <= 1.0e-9_dp, 'worst relative error '//table_real(worst))

    ! Energy per m of thickness: W = p0 b |u_top| (error < dt/t_end as the
    ! top's), kinetic = strain = W/2 less half of the numerical dissipation.
    associate (exact_work => p0*width*velocity*t_end)
    call check_close('wave_work', run%work, exact_work, dt/t_end)
    kinetic = history_last(record, 'kinetic_J')
    strain = history_last(record, 'strain_J')
    print '(a, 3es13.5, a, es10.3, a)', '# energy: work, kinetic, strain ', run%work, kinetic, strain, &
      ' J/m; Wilson-theta dissipated ', -run%balance/run%work, ' of the work'
    ! Wilson-theta's numerical damping is the (negative) balance error; it
    ! grows with the step (the sweep: 0.095 % of the work at C = 0.25,
    ! 0.8 % at C = 4), so at C = 0.2 it is below 0.1 %: bound 0.2 %.
    call check('wave_balance_is_dissipation', run%balance < 0.0_dp .and. -run%balance < 2.0e-3_dp*exact_work, &
               'balance error '//table_real(run%balance)//' J')
    ! Equipartition: each gets half of what is left (rho v^2/2 = sigma^2/(2 M_c)
    ! behind the front); 3e-3 covers the < 1e-3 dissipated plus the front's unequal share.
    call check_close('wave_kinetic_is_half_the_work', kinetic, 0.5_dp*exact_work, 3.0e-3_dp)
    call check_close('wave_strain_is_half_the_work', strain, 0.5_dp*exact_work, 3.0e-3_dp)
    ! Elastic: the stored energy is all the internal work (round-off).
    call check_close('wave_elastic_stores_all', history_last(record, 'dissipated_J'), 0.0_dp, 0.0_dp, &
                     1.0e-9_dp*exact_work)
    end associate
  end subroutine test_deck

  !> Wilson-theta's overshoot and smoothing of the front for several time
  !> steps (Courant numbers C = c dt/dz), theta = 1.4, and theta = 1.0 at
  !> C = 0.25, against the semi-discrete reference; the table for doc/verification.md.
  !>
  !> For small omega dt, Wilson-theta's amplification matrix (free vibration
  !> at omega, eqs. [34]-[42] with R = 0) has a period elongation
  !> a (omega dt)^2, a = 1/24 + theta (theta - 1)/4, and a damping ratio
  !> theta (theta - 1)(2 theta - 1)/12 (omega dt)^3 (the leading terms of its
  !> eigenvalues for small omega dt, confirmed in 40-digit arithmetic: a = 1/24
  !> at theta = 1, the linear acceleration method; a = 0.18167 and damping
  !> 0.084 (omega dt)^3 at theta = 1.4).
  !> The elongation adds to the lattice's omega = c k (1 - (k dz)^2/24): the
  !> dispersion grows by 1 + 24 a C^2, the Airy length (lag, rise) by its
  !> cube root, and the overshoot stays. The damping, relative to the
  !> dispersion ~1.6 C^3 k dz, is ~1 % at C = 0.25 (k dz ~ dz/L ~ 0.4).
  subroutine test_time_steps()
    real(dp), parameter :: courants(5) = [0.25_dp, 0.5_dp, 1.0_dp, 2.0_dp, 4.0_dp]
    type(run_t) :: runs(5), linear
    integer :: k, p
    real(dp) :: tolerance

    do k = 1, size(courants)
      call run_variant(1.4_dp, courants(k), runs(k))
      if (.not. runs(k)%ok) return
    end do
    call run_variant(1.0_dp, 0.25_dp, linear)
    if (.not. linear%ok) return

    print '(a)', ''
    print '(a)', 'Front of the half-space wave (inputs/halfspace_wave.inp: 400 elements, dz = 2.5 mm, '// &
      'c = 100 m/s, to t = 9 ms) at depths 0.25 / 0.50 / 0.75 m (100 / 200 / 300 elements):'
    print '(a)', ''
    print '(a)', '| theta | C = c dt/dz | dt (us) | overshoot (%) | 10-90 % rise (elements) | '// &
      'half-level lag (dz/c) | rise at 0.50 m predicted by period elongation | '// &
      'worst plateau error, sigma_z and v_z at 0.25/0.50 m (%) | dissipated (% of work) |'
    print '(a)', '|---|---|---|---|---|---|---|---|---|'
    print '(a)', '| Airy asymptote | 0 | - |'//cells([(100.0_dp*(airy_peak - 1.0_dp), p = 1, 3)])// &
      cells([((airy_xi10 - airy_xi90)*airy_scale(depths(p)), p = 1, 3)])// &
      cells([(-airy_xi50*airy_scale(depths(p)), p = 1, 3)])//' - | - | - |'
    print '(a)', '| semi-discrete (RK4) | 0 | - |'//cells(100.0_dp*reference%overshoot)// &
      cells(reference%rise*speed/dz)//cells((reference%arrival - depths/speed)*speed/dz)//' - | - | - |'
    do k = 1, size(runs)
      call print_row(runs(k))
    end do
    call print_row(linear)
    print '(a)', ''

    ! The semi-discrete reference is the Airy front to leading order; the
    ! corrections fall as N^(-2/3) (N = d/dz elements travelled: measured
    ! 1.5, 0.9, 0.7 % for N = 100, 200, 300), so N^(-2/3) (4.6 .. 2.2 %) bounds them.
    do p = 1, 3
      associate (n => depths(p)/dz, name => probe_names(p))
      call check_close('reference_airy_lag_'//name, (reference(p)%arrival - depths(p)/speed)*speed/dz, &
                       -airy_xi50*airy_scale(depths(p)), n**(-2.0_dp/3.0_dp))
      call check_close('reference_airy_rise_'//name, reference(p)%rise*speed/dz, &
                       (airy_xi10 - airy_xi90)*airy_scale(depths(p)), n**(-2.0_dp/3.0_dp))
      call check_close('reference_airy_peak_'//name, 1.0_dp + reference(p)%overshoot, airy_peak, n**(-2.0_dp/3.0_dp))
      end associate
    end do

    ! Small steps: the front is the reference's scaled by the period
    ! elongation. theta = 1: no damping, next-order terms (C^4, linear
    ! interpolation between rows) ~0.3 %: 1 %. theta = 1.4: the damping adds
    ! ~1 % (above): 2 %. Overshoot: theta = 1 keeps the reference's (within
    ! 0.5 points: the sampling of the peak by the rows); theta = 1.4's
    ! damping lowers it, by less than 0.5 points at C = 0.25.
    call check_period_elongation('linear_acceleration', linear, 1.0e-2_dp)
    call check_period_elongation('wilson_1_4', runs(1), 2.0e-2_dp)
    do p = 1, 3
      call check_close('linear_acceleration_overshoot_'//probe_names(p), linear%front(p)%overshoot, &
                       reference(p)%overshoot, 0.0_dp, 5.0e-3_dp)
      call check_close('wilson_1_4_overshoot_'//probe_names(p), runs(1)%front(p)%overshoot, &
                       reference(p)%overshoot, 0.0_dp, 5.0e-3_dp)
    end do
    ! No numerical damping at theta = 1: the balance error is only the
    ! bookkeeping's O(dt^2); at least ten times below theta = 1.4's dissipation at the same C.
    call check('linear_acceleration_conserves_energy', abs(linear%balance) < 0.1_dp*abs(runs(1)%balance), &
               'balance '//table_real(linear%balance)//' J vs '//table_real(runs(1)%balance)//' J at theta = 1.4')
    ! theta = 1.4 elongates the period more and damps: at the same C a wider front, a smaller overshoot.
    do p = 1, 3
      call check('theta_1_4_smooths_more_'//probe_names(p), runs(1)%front(p)%rise > linear%front(p)%rise .and. &
                 runs(1)%front(p)%overshoot < linear%front(p)%overshoot)
    end do

    do k = 1, size(runs)
      associate (run => runs(k), tag => 'C'//fixed(runs(k)%courant))
      do p = 1, 3
        associate (name => tag//'_'//probe_names(p), front => run%front(p))
        ! Period elongation and damping both widen the front and damping
        ! lowers the peak: never sharper, never a larger overshoot than the
        ! semi-discrete (exact-in-time) front.
        call check('wilson_smooths_'//name, front%rise >= reference(p)%rise .and. &
                   front%overshoot <= reference(p)%overshoot, 'rise '//table_real(front%rise*speed/dz)// &
                   ' elements, overshoot '//table_real(front%overshoot))
        ! The arrival stays right within the front: d/c lies within half a
        ! rise time of the half level, for every step ...
        call check('wilson_arrival_within_front_'//name, abs(front%arrival - depths(p)/speed) <= 0.5_dp*front%rise, &
                   'lag '//table_real(front%arrival - depths(p)/speed)//' s, rise '//table_real(front%rise)//' s')
        ! ... and within the a-priori bound of test_deck: the lattice's
        ! Airy lag (<= 1.4 dz/c here) plus the period elongation's, which
        ! saturates near one step at large C (0.9 .. 1.0 dt at d = 0.75 m for C = 1 .. 4).
        tolerance = 2.0_dp*dz/speed + 2.0_dp*run%dt
        call check('wilson_arrival_'//name, abs(front%arrival - depths(p)/speed) <= tolerance, &
                   'lag '//table_real(front%arrival - depths(p)/speed)//' s, tolerance '//table_real(tolerance)//' s')
        end associate
      end do
      ! The plateau is right for every step: means from 2 ms behind the
      ! front (which is at most 0.7 ms wide, C = 4) to the end, at the two
      ! upper probes (the front passes the third too late); the ringing
      ! left there is < 3 % and averages out over >= 2 ms: 1 %.
      do p = 1, 2
        call check('wilson_plateau_stress_'//tag//'_'//probe_names(p), abs(run%stress_error(p)) <= 1.0e-2_dp, &
                   'relative error '//table_real(run%stress_error(p)))
        call check('wilson_plateau_velocity_'//tag//'_'//probe_names(p), abs(run%velocity_error(p)) <= 1.0e-2_dp, &
                   'relative error '//table_real(run%velocity_error(p)))
      end do
      call check('wilson_dissipates_'//tag, run%balance < 0.0_dp, 'balance '//table_real(run%balance)//' J')
      end associate
    end do
    ! A larger step: a wider, smoother front, a smaller overshoot, more dissipation.
    do k = 2, size(runs)
      associate (tag => 'C'//fixed(runs(k - 1)%courant)//'_to_'//fixed(runs(k)%courant))
      call check('wilson_wider_front_'//tag, all(runs(k)%front%rise > runs(k - 1)%front%rise))
      call check('wilson_smaller_overshoot_'//tag, all(runs(k)%front%overshoot < runs(k - 1)%front%overshoot))
      call check('wilson_more_dissipation_'//tag, runs(k)%balance < runs(k - 1)%balance)
      end associate
    end do
  end subroutine test_time_steps

  !> Lag and rise of a run = the reference's times the Airy-length factor of
  !> Wilson-theta's period elongation, within rtol.
  subroutine check_period_elongation(name, run, rtol)
    character(*), intent(in) :: name
    type(run_t), intent(in) :: run
    real(dp), intent(in) :: rtol
    integer :: p
    do p = 1, 3
      call check_close(name//'_lag_'//probe_names(p), run%front(p)%arrival - depths(p)/speed, &
                       elongation_factor(run)*(reference(p)%arrival - depths(p)/speed), rtol)
      call check_close(name//'_rise_'//probe_names(p), run%front(p)%rise, elongation_factor(run)*reference(p)%rise, rtol)
    end do
  end subroutine check_period_elongation

  !> (1 + 24 a C^2)^(1/3), a = 1/24 + theta (theta - 1)/4: how much Wilson-theta's
  !> period elongation lengthens the Airy front (small C).
  pure real(dp) function elongation_factor(run)
    type(run_t), intent(in) :: run
    real(dp) :: a
    a = 1.0_dp/24.0_dp + run%theta*(run%theta - 1.0_dp)/4.0_dp
    elongation_factor = (1.0_dp + 24.0_dp*a*run%courant**2)**(1.0_dp/3.0_dp)
  end function elongation_factor

  !> One row of the table.
  subroutine print_row(run)
    type(run_t), intent(in) :: run
    character(len=40) :: head, tail
    write(head, '(a, f3.1, a, f4.2, a, f6.2, a)') '| ', run%theta, ' | ', run%courant, ' | ', 1.0e6_dp*run%dt, ' |'
    write(tail, '(f6.2, a, f6.3, a, f6.3, a)') elongation_factor(run)*reference(2)%rise*speed/dz, ' | ', &
      100.0_dp*max(maxval(abs(run%stress_error(1:2))), maxval(abs(run%velocity_error(1:2)))), ' | ', &
      -100.0_dp*run%balance/run%work, ' |'
    print '(a)', trim(head)//cells(100.0_dp*run%front%overshoot)//cells(run%front%rise*speed/dz)// &
      cells((run%front%arrival - depths/speed)*speed/dz)//' '//trim(adjustl(tail))
  end subroutine print_row

  !> Three values as one table cell, ' a / b / c |'.
  function cells(values) result(text)
    real(dp), intent(in) :: values(3)
    character(:), allocatable :: text
    character(len=40) :: buffer
    write(buffer, '(f6.2, " /", f6.2, " /", f6.2)') values
    text = ' '//trim(adjustl(buffer))//' |'
  end function cells

  !> A value with two decimals as text ('0.25', '4.00') for check names.
  function fixed(value) result(text)
    real(dp), intent(in) :: value
    character(:), allocatable :: text
    character(len=16) :: buffer
    write(buffer, '(f0.2)') value
    text = trim(buffer)
    if (text(1:1) == '.') text = '0'//text
  end function fixed

  !> Deck lines with the OUTPUT card replaced by OUTPUT EVERY=1.
  function every_step(deck_lines) result(variant)
    character(*), intent(in) :: deck_lines(:)
    character(len=200), allocatable :: variant(:)
    integer :: i
    variant = deck_lines
    do i = 1, size(variant)
      if (index(adjustl(variant(i)), 'OUTPUT ') == 1) variant(i) = 'OUTPUT EVERY=1'
    end do
  end function every_step

  !> The deck with its TIME and WILSON cards replaced, read and run.
  subroutine run_variant(theta, courant, run)
    real(dp), intent(in) :: theta, courant
    type(run_t), intent(out) :: run
    character(len=200), allocatable :: variant(:)
    character(:), allocatable :: path, tag
    type(deck_t) :: deck
    type(record_t) :: record
    type(error_t), allocatable :: error
    integer :: i
    run%theta = theta
    run%courant = courant
    tag = 'theta'//fixed(theta)//'_C'//fixed(courant)
    variant = every_step(lines)
    do i = 1, size(variant)
      if (index(adjustl(variant(i)), 'TIME ') == 1) &
        variant(i) = 'TIME DT='//short_real(courant*dz/speed)//' TEND='//short_real(t_end)
      if (index(adjustl(variant(i)), 'WILSON ') == 1) variant(i) = 'WILSON THETA='//short_real(theta)
    end do
    path = folder//'/wave_'//tag//'.inp'
    call write_deck(path, variant)
    call read_deck(path, deck, error)
    if (.not. allocated(error)) call solve_dynamic(deck, record, error)
    if (allocated(error)) then
      call check('wave_runs_'//tag, .false., error_text(error)); return
    end if
    call check_close('wave_step_'//tag, deck%stages(1)%dt, courant*dz/speed, 1.0e-12_dp)
    ! Plateau windows from 2 ms behind the front: see test_time_steps.
    call measure_run(deck, record, 2.0e-3_dp, run)
  end subroutine run_variant

  !> Fronts, plateau means from `delay` behind the front to the end, work and balance of a run.
  subroutine measure_run(deck, record, delay, run)
    type(deck_t), intent(in) :: deck
    type(record_t), intent(in) :: record
    real(dp), intent(in) :: delay
    type(run_t), intent(inout) :: run
    real(dp), allocatable :: t(:), sz(:), vz(:)
    integer :: p
    run%dt = deck%stages(1)%dt
    t = history_column(record, 't_s')
    do p = 1, 3
      sz = history_column(record, probe_names(p)//'_sz_Pa')
      vz = history_column(record, probe_names(p)//'_vz_m_s')
      run%front(p) = measure_front(t, -sz/p0)
      run%stress_error(p) = window_mean(t, -sz/p0, depths(p)/speed + delay) - 1.0_dp
      run%velocity_error(p) = window_mean(t, -vz/velocity, depths(p)/speed + delay) - 1.0_dp
    end do
    run%work = history_last(record, 'external_work_J')
    run%balance = history_last(record, 'balance_error_J')
    run%ok = .true.
  end subroutine measure_run

  !> The front in a normalised stress history s(t) (0 before, 1 after).
  pure function measure_front(t, s) result(front)
    real(dp), intent(in) :: t(:), s(:)
    type(front_t) :: front
    front%arrival = first_crossing(t, s, 0.5_dp)
    front%rise = first_crossing(t, s, 0.9_dp) - first_crossing(t, s, 0.1_dp)
    front%overshoot = maxval(s) - 1.0_dp
  end function measure_front

  !> The first time s reaches `level`, linear between rows (huge if never).
  pure real(dp) function first_crossing(t, s, level) result(time)
    real(dp), intent(in) :: t(:), s(:), level
    integer :: i
    time = huge(1.0_dp)
    do i = 2, size(t)
      if (s(i) >= level) then
        time = t(i - 1) + (level - s(i - 1))/(s(i) - s(i - 1))*(t(i) - t(i - 1))
        return
      end if
    end do
  end function first_crossing

  !> Mean of the rows with t >= start (a time average: the rows are equally spaced).
  pure real(dp) function window_mean(t, values, start) result(mean)
    real(dp), intent(in) :: t(:), values(:), start
    mean = sum(values, mask=t >= start)/max(count(t >= start), 1)
  end function window_mean

  !> The Airy length L/dz = (c dz^2 t/8)^(1/3)/dz at t = d/c: (d/(8 dz))^(1/3).
  pure real(dp) function airy_scale(depth)
    real(dp), intent(in) :: depth
    airy_scale = (depth/(8.0_dp*dz))**(1.0_dp/3.0_dp)
  end function airy_scale

  !> The semi-discrete column, exact in time: nz masses rho dz per unit area
  !> (rho dz/2 at the top), lumped as eq. [32], joined by springs M_c/dz, the
  !> bottom fixed, p0 on the top from t = 0; the probe stress is the mean of
  !> the two elements at the node, as the nodal stress of the FE run. RK4 at
  !> C = 0.05 (omega dt <= 0.1: its error ~(omega dt)^4/120 is negligible),
  !> checked against C = 0.1. The same measures as the FE runs (every step a row).
  subroutine semi_discrete_reference(fronts)
    type(front_t), intent(out) :: fronts(3)
    type(front_t) :: coarse(3)
    integer :: p
    call semi_discrete_fronts(0.05_dp, fronts)
    call semi_discrete_fronts(0.1_dp, coarse)
    ! Doubling the step changes the lags and rises by < 3e-4 and the
    ! overshoot by 1e-6 (mostly the linear interpolation between rows, ~dt^2):
    ! converged far below the 1 % comparisons made with it.
    do p = 1, 3
      associate (name => probe_names(p))
      call check_close('reference_converged_lag_'//name, coarse(p)%arrival - depths(p)/speed, &
                       fronts(p)%arrival - depths(p)/speed, 1.0e-3_dp)
      call check_close('reference_converged_rise_'//name, coarse(p)%rise, fronts(p)%rise, 1.0e-3_dp)
      call check_close('reference_converged_overshoot_'//name, coarse(p)%overshoot, fronts(p)%overshoot, &
                       0.0_dp, 1.0e-5_dp)
      end associate
    end do
  end subroutine semi_discrete_reference

  subroutine semi_discrete_fronts(courant, fronts)
    real(dp), intent(in) :: courant
    type(front_t), intent(out) :: fronts(3)
    real(dp) :: w(nz), v(nz), mass(nz), dw(nz, 4), dv(nz, 4), dt
    real(dp), allocatable :: t(:), s(:, :)
    integer :: nstep, k, p, node
    mass = rho*dz
    mass(1) = 0.5_dp*rho*dz
    dt = courant*dz/speed
    nstep = nint(t_end/dt)
    allocate(t(0:nstep), s(0:nstep, 3))
    w = 0.0_dp                              ! downward displacement, node 1 = top
    v = 0.0_dp
    do k = 0, nstep
      t(k) = k*dt
      associate (q => compression(w))
      do p = 1, 3
        node = nint(depths(p)/dz) + 1
        s(k, p) = 0.5_dp*(q(node - 1) + q(node))/p0
      end do
      end associate
      if (k == nstep) exit
      dw(:, 1) = v
      dv(:, 1) = acceleration(w, mass)
      dw(:, 2) = v + 0.5_dp*dt*dv(:, 1)
      dv(:, 2) = acceleration(w + 0.5_dp*dt*dw(:, 1), mass)
      dw(:, 3) = v + 0.5_dp*dt*dv(:, 2)
      dv(:, 3) = acceleration(w + 0.5_dp*dt*dw(:, 2), mass)
      dw(:, 4) = v + dt*dv(:, 3)
      dv(:, 4) = acceleration(w + dt*dw(:, 3), mass)
      w = w + dt/6.0_dp*(dw(:, 1) + 2.0_dp*dw(:, 2) + 2.0_dp*dw(:, 3) + dw(:, 4))
      v = v + dt/6.0_dp*(dv(:, 1) + 2.0_dp*dv(:, 2) + 2.0_dp*dv(:, 3) + dv(:, 4))
    end do
    do p = 1, 3
      fronts(p) = measure_front(t, s(:, p))
    end do
  end subroutine semi_discrete_fronts

  !> Compressive stress of each element of the chain (element e joins nodes
  !> e and e + 1; node nz + 1, the bottom, is fixed).
  pure function compression(w) result(q)
    real(dp), intent(in) :: w(:)
    real(dp) :: q(size(w))
    q = modulus*(w - [w(2:), 0.0_dp])/dz
  end function compression

  !> Downward acceleration of the chain's nodes: p0 on the top, the element
  !> above pushes down, the one below pushes up.
  pure function acceleration(w, mass) result(a)
    real(dp), intent(in) :: w(:), mass(:)
    real(dp) :: a(size(w)), q(size(w))
    q = compression(w)
    a = [0.0_dp, q(:size(w) - 1)] - q
    a(1) = a(1) + p0
    a = a/mass
  end function acceleration
end program test_wave
