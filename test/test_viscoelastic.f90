!> Verification of the viscoelastic law (eqs. [13]-[24]) and the quasi-static
!> time loop, against closed forms and the correspondence principle:
!>   - J(x) = (1 - exp(-x))/x and exp(y) - 1 against quadruple precision;
!>   - step-strain relaxation, over t = 1e-7 .. 1e4 s: sigma_z - sigma_r = 2 eps phi1(t);
!>   - constant strain rate: the closed-form hereditary integral;
!>   - creep under a constant load: the exact one-term creep compliance;
!>   - an elastic body through QUASISTATIC equals STATIC at every step;
!>   - a thick viscoelastic cylinder under a pressure step: bore displacement
!>     within 1 % of the correspondence-principle solution;
!>   - the elastic path allocates no history, beta = 0 terms carry none.
!> Uniform-strain problems are exact in space (patch test) and the incremental
!> law is exact for strain histories linear within each step (a step is the
!> dt = 0 increment at t = 0), so those comparisons sit at round-off: the
!> 1e-9 tolerances leave room for the K/phi1 cancellation in sigma_z - sigma_r
!> and for summation over ~100 steps, nothing more.
program test_viscoelastic
  use visco2d_kinds, only: dp
  use visco2d_error, only: error_t, error_text
  use visco2d_strings, only: integer_text, table_real
  use visco2d_deck, only: deck_t, read_deck, analysis_quasistatic, total_steps
  use visco2d_material, only: material_t, has_memory, shear_relaxation_modulus
  use visco2d_viscoelastic, only: relaxation_integral, exp_minus_one, step_coefficients, step_coefficients_t, &
                                  viscoelastic_state_t, viscoelastic_state_create
  use visco2d_static, only: solve_static, static_solution_t
  use visco2d_quasistatic, only: solve_quasistatic
  use visco2d_scene, only: scene_effects, effects_text
  use visco2d_record, only: record_t
  use visco2d_expect, only: summary_value
  use visco2d_analytic, only: shear_relaxation, shear_ramp_response, uniaxial_creep_compliance_one_term, &
                              cylinder_bore_displacement
  use visco2d_testing, only: check, check_close, test_summary, write_deck, history_column
  implicit none

  integer, parameter :: qp = selected_real_kind(30)
  character(*), parameter :: folder = 'build/test_decks/viscoelastic'
  character(len=100), parameter :: decades(11) = [character(len=100) :: &
    'TIME DT=1e-7 TEND=1e-6', 'TIME DT=1e-6 TEND=1e-5', 'TIME DT=1e-5 TEND=1e-4', 'TIME DT=1e-4 TEND=1e-3', &
    'TIME DT=1e-3 TEND=1e-2', 'TIME DT=1e-2 TEND=1e-1', 'TIME DT=1e-1 TEND=1', 'TIME DT=1 TEND=10', &
    'TIME DT=10 TEND=100', 'TIME DT=100 TEND=1000', 'TIME DT=1000 TEND=10000']
  ! Table 3 of the paper (0.7 and 1.2 m/s).
  real(dp), parameter :: table3_shear_07(4) = [0.636e6_dp, 0.111e6_dp, 0.208e6_dp, 0.099e6_dp]
  real(dp), parameter :: table3_rate_07(4) = [0.000347_dp, 0.0409_dp, 1.121_dp, 35.26_dp]
  real(dp), parameter :: table3_shear_12(4) = [0.710e6_dp, 0.134e6_dp, 0.265e6_dp, 0.119e6_dp]
  real(dp), parameter :: table3_rate_12(4) = [0.000380_dp, 0.0420_dp, 1.633_dp, 41.30_dp]

  call execute_command_line('mkdir -p '//folder)

  call test_kernels()
  call test_step_relaxation('relaxation_one_term', [1.0e6_dp], [1.0e-3_dp], 2.0e6_dp)
  call test_step_relaxation('relaxation_four_terms', [0.4e6_dp, 0.3e6_dp, 0.2e6_dp, 0.1e6_dp], &
                            [1.0e-3_dp, 1.0e-1_dp, 1.0e1_dp, 1.0e3_dp], 2.0e6_dp)
  call test_step_relaxation('relaxation_table3_07', table3_shear_07, table3_rate_07, 1.756e6_dp)
  call test_step_relaxation('relaxation_table3_12', table3_shear_12, table3_rate_12, 2.047e6_dp)
  call test_relaxation_deck()
  call test_constant_strain_rate()
  call test_creep()
  call test_elastic_quasistatic_equals_static()
  call test_cylinder()
  call test_no_history_without_memory()
  call test_uniaxial_materials()
  call test_uniaxial_relaxation()
  call test_summary('test_viscoelastic')

contains

  !> J(x) and exp(y) - 1 to a few ulps from x = 1e-14 to 1e6 (quadruple-precision reference).
  subroutine test_kernels()
    real(dp) :: x, worst_j, worst_e, value
    real(qp) :: xq, exact
    integer :: k
    worst_j = 0.0_dp
    worst_e = 0.0_dp
    do k = -56, 24                       ! x = 10^(k/4): 1e-14 .. 1e6
      x = 10.0_dp**(k/4.0_dp)
      xq = real(x, qp)
      exact = (1.0_qp - exp(-xq))/xq
      worst_j = max(worst_j, real(abs(real(relaxation_integral(x), qp)/exact - 1.0_qp), dp))
      exact = exp(-xq) - 1.0_qp
      value = exp_minus_one(-x)
      worst_e = max(worst_e, real(abs(real(value, qp)/exact - 1.0_qp), dp))
    end do
    print '(a, es9.2, a, es9.2)', '# J(x) worst relative error ', worst_j, ';  expm1 ', worst_e
    ! A naive (1 - exp(-x))/x is wrong by ~1e-8 at x = 3.5e-9 (Table 3, dt = 1e-5 s); these stay at a few ulps.
    call check('relaxation_integral_ulps', worst_j < 1.0e-15_dp, 'worst relative error '//table_real(worst_j))
    call check('exp_minus_one_ulps', worst_e < 1.0e-15_dp, 'worst relative error '//table_real(worst_e))
    call check('relaxation_integral_zero', relaxation_integral(0.0_dp) == 1.0_dp)
    call check_close('relaxation_integral_huge', relaxation_integral(1.0e300_dp), 1.0e-300_dp, 1.0e-15_dp)
    call check('exp_minus_one_underflow', exp_minus_one(-1.0e6_dp) == -1.0_dp)
  end subroutine test_kernels

  !> A confined block (u_r = 0 on its side) under a step eps_z = -0.01 held
  !> from t = 0: sigma_z - sigma_r = 2 eps phi1(t) and the mean stress K eps
  !> at every step, t = 1e-7 .. 1e4 s.
  subroutine test_step_relaxation(name, shear, rate, bulk)
    character(*), intent(in) :: name
    real(dp), intent(in) :: shear(:), rate(:), bulk
    character(len=100), allocatable :: lines(:)
    type(record_t) :: record
    real(dp), allocatable :: t(:), sr(:), sz(:), st(:)
    real(dp) :: strain, exact, worst_deviatoric, worst_mean
    integer :: m, row
    strain = -0.01_dp
    lines = [character(len=100) :: 'TITLE '//name, 'ANALYSIS QUASISTATIC', 'GEOMETRY AXISYMMETRIC', &
             'MATERIAL flesh VISCOELASTIC K='//table_real(bulk)]
    do m = 1, size(shear)
      lines = [character(len=100) :: lines, 'PRONY G='//table_real(shear(m))//' BETA='//table_real(rate(m))]
    end do
    lines = [character(len=100) :: lines, 'MESH RECT R0=0 R1=0.01 Z0=0 Z1=0.01 NR=2 NZ=2', 'FIX BOTTOM Z', &
             'FIX OUTER R', 'FIX TOP Z UZ=-1e-4', decades, 'PROBE c R=0.005 Z=0.005', 'END']
    if (.not. run(name, lines, record)) return
    t = history_column(record, 't_s')
    sr = history_column(record, 'c_sr_Pa')
    sz = history_column(record, 'c_sz_Pa')
    st = history_column(record, 'c_st_Pa')
    call check(name//'_rows', size(t) == 101, 'rows '//integer_text(size(t)))   ! step 0, 10 + 10 x 9 steps
    call check(name//'_time_span', t(2) == 1.0e-7_dp .and. t(size(t)) == 1.0e4_dp)
    worst_deviatoric = 0.0_dp
    worst_mean = 0.0_dp
    do row = 1, size(t)
      exact = 2.0_dp*strain*shear_relaxation(shear, rate, t(row))
      worst_deviatoric = max(worst_deviatoric, abs((sz(row) - sr(row))/exact - 1.0_dp))
      worst_mean = max(worst_mean, abs((sz(row) + sr(row) + st(row))/(3.0_dp*bulk*strain) - 1.0_dp))
    end do
    print '(a, es9.2, a, es9.2)', '# '//name//': worst relative error, deviatoric ', worst_deviatoric, &
      ', mean ', worst_mean
    call check(name//'_follows_phi1', worst_deviatoric < 1.0e-9_dp, 'worst relative error '//table_real(worst_deviatoric))
    call check(name//'_mean_stress_elastic', worst_mean < 1.0e-12_dp, 'worst relative error '//table_real(worst_mean))
    ! Eleven stages of different dt after the dt = 0 step: 12 factorizations, no more.
    call check(name//'_factorizations', summary_value(record, 'factorizations') == '12', &
               'factorizations = '//summary_value(record, 'factorizations'))
  end subroutine test_step_relaxation

  !> The archived relaxation deck (inputs/relaxation_step.inp) reads as intended.
  subroutine test_relaxation_deck()
    type(deck_t) :: deck
    type(error_t), allocatable :: error
    call read_deck('inputs/relaxation_step.inp', deck, error)
    call check('relaxation_deck_reads', .not. allocated(error))
    if (allocated(error)) return
    call check('relaxation_deck_quasistatic', deck%analysis == analysis_quasistatic)
    call check('relaxation_deck_steps', total_steps(deck) == 100 .and. size(deck%stages) == 11)
    call check('relaxation_deck_effects', effects_text(scene_effects(deck)) == 'viscoelastic', &
               effects_text(scene_effects(deck)))
    call check_close('relaxation_deck_phi1_at_0', shear_relaxation_modulus(deck%materials(1), 0.0_dp), &
                     sum(table3_shear_07), 1.0e-15_dp)
  end subroutine test_relaxation_deck

  !> Confined block compressed at a constant rate from t = 0 (CURVE ramp):
  !> sigma_z - sigma_r = 2 int_0^t phi1(t - tau) rate dtau, in closed form.
  subroutine test_constant_strain_rate()
    character(len=100), allocatable :: lines(:)
    type(record_t) :: record
    real(dp), allocatable :: t(:), sr(:), sz(:)
    real(dp), parameter :: shear(3) = [0.5e6_dp, 0.3e6_dp, 0.2e6_dp], rate(3) = [0.05_dp, 2.0_dp, 80.0_dp]
    real(dp) :: strain_rate, exact, worst
    integer :: row
    strain_rate = -1.0e-3_dp             ! UZ = -1e-4 m at t = 10 s on a 0.01 m block
    lines = [character(len=100) :: 'TITLE constant strain rate', 'ANALYSIS QUASISTATIC', 'GEOMETRY AXISYMMETRIC', &
             'MATERIAL flesh VISCOELASTIC K=3e6', 'PRONY G=0.5e6 BETA=0.05', 'PRONY G=0.3e6 BETA=2', &
             'PRONY G=0.2e6 BETA=80', 'MESH RECT R0=0 R1=0.01 Z0=0 Z1=0.01 NR=3 NZ=2', 'FIX BOTTOM Z', &
             'FIX OUTER R', 'FIX TOP Z UZ=-1e-4 CURVE=ramp', 'CURVE ramp 0 0 10 1', &
             'TIME DT=1e-3 TEND=0.1', 'TIME DT=0.01 TEND=1', 'TIME DT=0.1 TEND=10', 'PROBE c R=0.005 Z=0.005', 'END']
    if (.not. run('constant_strain_rate', lines, record)) return
    t = history_column(record, 't_s')
    sr = history_column(record, 'c_sr_Pa')
    sz = history_column(record, 'c_sz_Pa')
    worst = 0.0_dp
    do row = 2, size(t)
      exact = shear_ramp_response(shear, rate, strain_rate, t(row))
      worst = max(worst, abs((sz(row) - sr(row))/exact - 1.0_dp))
    end do
    print '(a, es9.2)', '# constant strain rate: worst relative error ', worst
    call check('constant_strain_rate_hereditary_integral', worst < 1.0e-9_dp, 'worst relative error '//table_real(worst))
    call check('constant_strain_rate_starts_at_zero', abs(sz(1)) + abs(sr(1)) == 0.0_dp)
  end subroutine test_constant_strain_rate

  !> Free cylinder on a frictionless base, constant top pressure p from t = 0
  !> (one-term Maxwell shear): u_z(top) = -p H D(t), D = (1 + beta t)/(3G) + 1/(9K),
  !> and u_r(side) = R p [(1 + beta t)/(6G) - 1/(9K)].
  subroutine test_creep()
    character(len=100), allocatable :: lines(:)
    type(record_t) :: record
    real(dp), allocatable :: t(:), uz(:), ur(:)
    real(dp), parameter :: shear = 0.8e6_dp, rate = 4.0_dp, bulk = 2.5e6_dp, pressure = 1.0e4_dp
    real(dp), parameter :: height = 0.02_dp, radius = 0.01_dp
    real(dp) :: worst_axial, worst_radial, compliance
    integer :: row
    lines = [character(len=100) :: 'TITLE creep', 'ANALYSIS QUASISTATIC', 'GEOMETRY AXISYMMETRIC', &
             'MATERIAL flesh VISCOELASTIC K=2.5e6', 'PRONY G=0.8e6 BETA=4', &
             'MESH RECT R0=0 R1=0.01 Z0=0 Z1=0.02 NR=3 NZ=4', 'FIX BOTTOM Z', 'PRESSURE TOP P=1e4', &
             'TIME DT=0.01 TEND=1', 'TIME DT=0.5 TEND=50', 'PROBE corner R=0.01 Z=0.02', 'END']
    if (.not. run('creep', lines, record)) return
    t = history_column(record, 't_s')
    uz = history_column(record, 'corner_uz_m')
    ur = history_column(record, 'corner_ur_m')
    worst_axial = 0.0_dp
    worst_radial = 0.0_dp
    do row = 1, size(t)
      compliance = uniaxial_creep_compliance_one_term(shear, rate, bulk, t(row))
      worst_axial = max(worst_axial, abs(uz(row)/(-pressure*height*compliance) - 1.0_dp))
      worst_radial = max(worst_radial, abs(ur(row)/(radius*pressure*((1.0_dp + rate*t(row))/(6.0_dp*shear) - &
                                                                      1.0_dp/(9.0_dp*bulk))) - 1.0_dp))
    end do
    print '(a, es9.2, a, es9.2)', '# creep: worst relative error, axial ', worst_axial, ', radial ', worst_radial
    call check('creep_axial_compliance', worst_axial < 1.0e-9_dp, 'worst relative error '//table_real(worst_axial))
    call check('creep_radial_compliance', worst_radial < 1.0e-9_dp, 'worst relative error '//table_real(worst_radial))
    call check_close('creep_final_strain', uz(size(uz))/(-height), &
                     pressure*((1.0_dp + rate*50.0_dp)/(3.0_dp*shear) + 1.0_dp/(9.0_dp*bulk)), 1.0e-9_dp)
  end subroutine test_creep

  !> An elastic sphere under a ramped-then-reduced pressure: each QUASISTATIC
  !> step equals curve(t) times the STATIC solution (linearity), with one
  !> factorization in all and no history.
  subroutine test_elastic_quasistatic_equals_static()
    character(len=100), allocatable :: common(:), lines(:)
    type(record_t) :: record
    type(deck_t) :: deck
    type(static_solution_t) :: solution
    type(error_t), allocatable :: error
    real(dp), allocatable :: t(:), ur(:), uz(:), sz(:), reference(:)
    real(dp) :: factor, worst, scale
    integer :: row, node
    common = [character(len=100) :: 'GEOMETRY AXISYMMETRIC', 'MATERIAL fruit ELASTIC E=18.11e6 NU=0.219', &
              'MESH SPHERE R=0.0366 LEVEL=2', 'FIX TOP Z', 'PROBE side R=0.0366 Z=0.0366', 'PROBE pole R=0 Z=0']
    lines = [character(len=100) :: 'TITLE static', 'ANALYSIS STATIC', common, 'PRESSURE OUTER P=1e5', 'END']
    call write_deck(folder//'/elastic_static.inp', lines)
    call read_deck(folder//'/elastic_static.inp', deck, error)
    call check('elastic_static_reads', .not. allocated(error))
    if (allocated(error)) return
    call solve_static(deck%mesh, deck%materials, deck%settings, deck%loads, deck%source, solution, error)
    call check('elastic_static_solves', .not. allocated(error))
    if (allocated(error)) return
    lines = [character(len=100) :: 'TITLE quasistatic', 'ANALYSIS QUASISTATIC', common, &
             'PRESSURE OUTER P=1e5 CURVE=load', 'CURVE load 0 0 1 1 3 0.25', 'TIME DT=0.1 TEND=2', &
             'TIME DT=0.25 TEND=4', 'END']
    if (.not. run('elastic_quasistatic', lines, record)) return
    call check('elastic_quasistatic_one_factorization', summary_value(record, 'factorizations') == '1', &
               'factorizations = '//summary_value(record, 'factorizations'))
    call read_deck(folder//'/elastic_quasistatic.inp', deck, error)
    call check('elastic_quasistatic_effects', effects_text(scene_effects(deck)) == 'none', &
               effects_text(scene_effects(deck)))
    call read_deck(folder//'/elastic_static.inp', deck, error)
    t = history_column(record, 't_s')
    worst = 0.0_dp
    scale = maxval(abs(solution%displacement))
    do row = 1, size(t)
      if (t(row) <= 1.0_dp) then
        factor = t(row)
      else
        factor = 1.0_dp - 0.75_dp*min(t(row) - 1.0_dp, 2.0_dp)/2.0_dp
      end if
      ur = history_column(record, 'side_ur_m')
      uz = history_column(record, 'pole_uz_m')
      sz = history_column(record, 'pole_sz_Pa')
      node = deck%probes(1)%node
      worst = max(worst, abs(ur(row) - factor*solution%displacement(1, node))/scale)
      node = deck%probes(2)%node
      worst = max(worst, abs(uz(row) - factor*solution%displacement(2, node))/scale)
      worst = max(worst, abs(sz(row) - factor*solution%nodal_stress(2, node))/maxval(abs(solution%nodal_stress)))
    end do
    print '(a, es9.2)', '# elastic QUASISTATIC vs STATIC: worst relative difference ', worst
    call check('elastic_quasistatic_equals_static', worst < 1.0e-12_dp, 'worst relative difference '//table_real(worst))
    ! The final snapshot (t = 4 s, curve 0.25) against the whole static field.
    reference = reshape(0.25_dp*solution%displacement, [size(solution%displacement)])
    associate (final => record%snapshots(size(record%snapshots)))
    call check('elastic_quasistatic_final_field', &
               maxval(abs(reshape(final%displacement, [size(reference)]) - reference)) < 1.0e-12_dp*scale)
    end associate
  end subroutine test_elastic_quasistatic_equals_static

  !> inputs/viscoelastic_cylinder.inp against the correspondence principle:
  !> the bore displacement at every step within 1 %.
  subroutine test_cylinder()
    type(deck_t) :: deck
    type(record_t) :: record
    type(error_t), allocatable :: error
    real(dp), allocatable :: t(:), bore(:), exact(:)
    real(dp) :: worst
    call read_deck('inputs/viscoelastic_cylinder.inp', deck, error)
    call check('cylinder_deck_reads', .not. allocated(error))
    if (allocated(error)) return
    call solve_quasistatic(deck%mesh, deck%materials, deck%settings, deck%loads, deck%probes, deck%stages, &
      deck%source, record, error)
    call check('cylinder_solves', .not. allocated(error))
    if (allocated(error)) return
    t = history_column(record, 't_s')
    bore = history_column(record, 'bore_ur_m')
    allocate(exact(size(t)))
    call cylinder_bore_displacement([0.2e6_dp, 1.0e6_dp, 0.5e6_dp], [0.0_dp, 10.0_dp, 0.1_dp], 5.0e6_dp, &
                                    0.01_dp, 0.02_dp, 1.0e4_dp, t, exact)
    worst = maxval(abs(bore/exact - 1.0_dp))
    print '(a, es9.2, a, i0, a)', '# viscoelastic cylinder: worst relative error of u(a, t) ', worst, ' over ', &
      size(t), ' steps'
    call check('cylinder_bore_within_1_percent', worst < 1.0e-2_dp, 'worst relative error '//table_real(worst))
    call check('cylinder_bore_creeps', bore(size(bore)) > 7.0_dp*bore(1))
  end subroutine test_cylinder

  !> Elastic materials and beta = 0 terms have no memory: no history storage.
  subroutine test_no_history_without_memory()
    type(material_t) :: materials(2)
    type(viscoelastic_state_t) :: state
    type(step_coefficients_t) :: coefficients
    materials(1)%shear = 1.0e6_dp
    materials(1)%long_term_shear = 1.0e6_dp
    materials(1)%bulk = 2.0e6_dp
    materials(2) = materials(1)
    materials(2)%long_term_shear = 0.5e6_dp
    materials(2)%prony_shear = [0.5e6_dp]
    materials(2)%prony_rate = [3.0_dp]
    call viscoelastic_state_create(materials, [1, 1, 1], state)
    call check('elastic_mesh_has_no_history', size(state%history, 2) == 0)
    call viscoelastic_state_create(materials, [1, 2, 1, 2], state)
    call check('history_only_for_memory_elements', size(state%history, 2) == 2*4 .and. &
               all(state%first == [1, 1, 5, 5, 9]))
    coefficients = step_coefficients(materials(1), 0.1_dp)
    call check('elastic_step_modulus', coefficients%shear == 1.0e6_dp .and. size(coefficients%integral) == 0)
    coefficients = step_coefficients(materials(2), 0.0_dp)
    call check('instantaneous_step_modulus', coefficients%shear == 1.0e6_dp)
    coefficients = step_coefficients(materials(2), 1.0e9_dp)
    call check_close('long_step_modulus', coefficients%shear, 0.5e6_dp + 0.5e6_dp/3.0e9_dp, 1.0e-14_dp)
    call check('elastic_has_no_memory', .not. has_memory(materials(1)) .and. has_memory(materials(2)))
  end subroutine test_no_history_without_memory

  !> UNIAXIAL cards: K from the Table 3 footnote, the instantaneous shear
  !> modulus G(0) = 3K E(0)/(9K - E(0)) (elastic relation at t = 0, independent
  !> of the pole finding), the elastic limit alpha = 0, and beta = 0 terms
  !> folded into the long-term modulus.
  subroutine test_uniaxial_materials()
    type(deck_t) :: deck
    type(error_t), allocatable :: error
    character(len=100), allocatable :: head(:)
    real(dp) :: young0, bulk
    head = [character(len=100) :: 'TITLE u', 'ANALYSIS QUASISTATIC', 'MESH RECT R0=0 R1=1 Z0=0 Z1=1 NR=1 NZ=1', &
            'FIX BOTTOM Z', 'TIME DT=1 TEND=1']
    call write_deck(folder//'/uniaxial_table4.inp', [character(len=100) :: head, &
      'MATERIAL apple UNIAXIAL NU=0.25', 'PRONY E=1.703e6 ALPHA=0.000311', 'PRONY E=0.258e6 ALPHA=0.0401', &
      'PRONY E=0.461e6 ALPHA=1.075', 'PRONY E=0.212e6 ALPHA=34.49', 'END'])
    call read_deck(folder//'/uniaxial_table4.inp', deck, error)
    call check('uniaxial_table4_reads', .not. allocated(error))
    if (allocated(error)) return
    young0 = 1.703e6_dp + 0.258e6_dp + 0.461e6_dp + 0.212e6_dp
    bulk = young0/(3.0_dp*(1.0_dp - 2.0_dp*0.25_dp))
    associate (m => deck%materials(1))
    call check_close('uniaxial_table4_bulk', m%bulk, bulk, 1.0e-15_dp)
    call check_close('uniaxial_table4_instantaneous_shear', m%shear, 3.0_dp*bulk*young0/(9.0_dp*bulk - young0), &
                     1.0e-13_dp)
    call check_close('uniaxial_table4_instantaneous_nu', m%poisson, 0.25_dp, 1.0e-13_dp)
    call check('uniaxial_table4_terms', size(m%prony_rate) == 4 .and. m%long_term_shear == 0.0_dp)
    call check('uniaxial_table4_sorted', all(m%prony_rate(2:) > m%prony_rate(:3)))
    end associate
    call write_deck(folder//'/uniaxial_elastic.inp', [character(len=100) :: head, &
      'MATERIAL solid UNIAXIAL NU=0.3', 'PRONY E=2e6 ALPHA=0', 'END'])
    call read_deck(folder//'/uniaxial_elastic.inp', deck, error)
    call check('uniaxial_elastic_reads', .not. allocated(error))
    if (allocated(error)) return
    call check_close('uniaxial_elastic_limit', deck%materials(1)%long_term_shear, 2.0e6_dp/2.6_dp, 1.0e-14_dp)
    call check('uniaxial_elastic_no_memory', .not. has_memory(deck%materials(1)) .and. &
               effects_text(scene_effects(deck)) == 'none')
    call write_deck(folder//'/long_term_term.inp', [character(len=100) :: head, &
      'MATERIAL solid VISCOELASTIC K=3e6', 'PRONY G=1e6 BETA=5', 'PRONY G=0.5e6 BETA=0', 'END'])
    call read_deck(folder//'/long_term_term.inp', deck, error)
    call check('long_term_term_reads', .not. allocated(error))
    if (allocated(error)) return
    call check('long_term_term_folded', deck%materials(1)%long_term_shear == 0.5e6_dp .and. &
               size(deck%materials(1)%prony_rate) == 1 .and. deck%materials(1)%shear == 1.5e6_dp)
  end subroutine test_uniaxial_materials

  !> The whole chain on the paper's own data: a free block of UNIAXIAL
  !> material (Table 4, 0.7 m/s) held at a step eps_z must relax as
  !> sigma_z(t) = eps_z E(t), eq. [47], the definition of the data. The
  !> lateral strain now varies in time (the Poisson ratio relaxes), so the
  !> strain is not linear within a step and the time error is O(dt^2): shown
  !> by 10 and 40 steps per decade.
  subroutine test_uniaxial_relaxation()
    real(dp) :: error_coarse, error_fine, order
    error_coarse = uniaxial_relaxation_error(10)
    error_fine = uniaxial_relaxation_error(40)
    order = log(error_coarse/error_fine)/log(4.0_dp)
    print '(a, es9.2, a, es9.2, a, f5.2)', '# uniaxial relaxation vs eps E(t): 10 steps/decade ', error_coarse, &
      ', 40 steps/decade ', error_fine, ', observed order ', order
    call check('uniaxial_relaxation_10_per_decade', error_coarse < 3.0e-3_dp, table_real(error_coarse))
    call check('uniaxial_relaxation_40_per_decade', error_fine < 2.0e-4_dp, table_real(error_fine))
    call check('uniaxial_relaxation_second_order', abs(order - 2.0_dp) < 0.2_dp, 'order '//table_real(order))
  end subroutine test_uniaxial_relaxation

  real(dp) function uniaxial_relaxation_error(per_decade) result(worst)
    integer, intent(in) :: per_decade
    character(len=100), allocatable :: lines(:)
    type(record_t) :: record
    real(dp), allocatable :: t(:), sz(:)
    real(dp), parameter :: young(4) = [1.703e6_dp, 0.258e6_dp, 0.461e6_dp, 0.212e6_dp]
    real(dp), parameter :: rate(4) = [0.000311_dp, 0.0401_dp, 1.075_dp, 34.49_dp]
    real(dp) :: stage_end
    integer :: k, row
    lines = [character(len=100) :: 'TITLE uniaxial relaxation', 'ANALYSIS QUASISTATIC', 'GEOMETRY AXISYMMETRIC', &
             'MATERIAL apple UNIAXIAL NU=0.25', 'PRONY E=1.703e6 ALPHA=0.000311', 'PRONY E=0.258e6 ALPHA=0.0401', &
             'PRONY E=0.461e6 ALPHA=1.075', 'PRONY E=0.212e6 ALPHA=34.49', &
             'MESH RECT R0=0 R1=0.01 Z0=0 Z1=0.01 NR=2 NZ=2', 'FIX BOTTOM Z', 'FIX TOP Z UZ=-1e-4', &
             'PROBE c R=0.005 Z=0.005']
    do k = 0, 9                                     ! decades 1e-5 .. 1e4 s
      stage_end = 10.0_dp**(k - 5)
      lines = [character(len=100) :: lines, 'TIME DT='//table_real(stage_end*merge(1.0_dp, 0.9_dp, k == 0)/per_decade)// &
               ' TEND='//table_real(stage_end)]
    end do
    lines = [character(len=100) :: lines, 'END']
    worst = huge(1.0_dp)
    if (.not. run('uniaxial_relaxation_'//integer_text(per_decade), lines, record)) return
    t = history_column(record, 't_s')
    sz = history_column(record, 'c_sz_Pa')
    worst = 0.0_dp
    do row = 1, size(t)
      worst = max(worst, abs(sz(row)/(-0.01_dp*sum(young*exp(-rate*t(row)))) - 1.0_dp))
    end do
  end function uniaxial_relaxation_error

  ! ------------------------------------------------------------------ helpers

  !> Write a deck, read it and run it quasi-statically; false (and a FAIL line) on any error.
  logical function run(name, lines, record) result(ok)
    character(*), intent(in) :: name
    character(*), intent(in) :: lines(:)
    type(record_t), intent(out) :: record
    type(deck_t) :: deck
    type(error_t), allocatable :: error
    call write_deck(folder//'/'//name//'.inp', lines)
    call read_deck(folder//'/'//name//'.inp', deck, error)
    if (.not. allocated(error)) call solve_quasistatic(deck%mesh, deck%materials, deck%settings, deck%loads, &
      deck%probes, deck%stages, deck%source, record, error)
    ok = .not. allocated(error)
    if (ok) then
      call check(name//'_runs', .true.)
    else
      call check(name//'_runs', .false., error_text(error))
    end if
  end function run

end program test_viscoelastic
