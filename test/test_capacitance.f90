!> The capacitance (Schur-complement) treatment of the contact equations
!> (src/contact/visco2d_capacitance.f90) gives the same answer as eliminating them
!> from S~ and refactoring (src/base/visco2d_banded.f90, band_constrain):
!>
!>  1. Algebra, on the band, profile and CHOLMOD factors (visco2d_factor): a
!>     banded SPD matrix (n = 120, kd = 9, diagonally dominant,
!>     condition number ~10), supports with prescribed values eliminated in
!>     both, and sets of held equations with values. Both solve the same
!>     well-conditioned system with a backward-stable method, so they agree
!>     to a few ulps of the solution scale: 1e-12 relative (100x the unit
!>     round-off times the condition number). Also checked: the held values
!>     come out exactly, lambda is the reaction (A u - f on the held rows),
!>     and columns are reused: a node leaving and coming back costs no new
!>     back-substitution.
!>  1b. Multi-point constraints (a body node on a pad's surface segment,
!>     u_c - w1 u_p1 - w2 u_p2 = value): the same, against an independent
!>     dense solve of the saddle-point (KKT) system [A -E; E^T 0] by QR
!>     (dgels), to 1e-10 relative (its condition number is ~1e3 here, both
!>     methods backward stable); the constraints hold to round-off, and the
!>     force is equal and opposite: the residual A u - f is lambda on the
!>     body's equation and -w lambda on each partner, to 1e-10 of |f|.
!>  2. Dynamics: the Table 1 impact (level 2) with STICK to maximum
!>     deformation and with SLIP + RELEASE=YES to separation, run both ways
!>     (solve_dynamic's hold: visco2d_refactoring). The contact decisions are the same
!>     (iterations, steps, node counts), the histories of alpha, force and q
!>     agree to 1e-9 of their largest value (round-off grows over ~300
!>     steps, far below any physical change), and the capacitance run
!>     factors S~ once where refactoring factors it at every contact change.
program test_capacitance
  use visco2d_kinds, only: dp
  use visco2d_error, only: error_t, error_text
  use visco2d_banded, only: band_matrix_t, band_create, band_constrain, band_constrain_rhs, band_factor, band_solve, &
                            band_multiply
  use visco2d_factor, only: factor_t, factor_compute, factor_solve, solver_band, solver_profile, solver_cholmod, solver_name
  use visco2d_capacitance, only: capacitance_t, capacitance_reset, capacitance_set, capacitance_apply, &
                                 capacitance_partners
  use visco2d_lapack, only: dgels
  use visco2d_deck, only: deck_t, read_deck
  use visco2d_dynamic, only: solve_dynamic
  use visco2d_refactoring, only: refactoring_hold_t
  use visco2d_record, only: record_t
  use visco2d_expect, only: summary_value
  use visco2d_testing, only: check, check_close, test_summary, write_deck, history_column
  implicit none

  character(*), parameter :: folder = 'build/test-tmp/test_capacitance'

  call execute_command_line('mkdir -p '//folder)
  call test_algebra(solver_band)
  call test_algebra(solver_profile)
  call test_algebra(solver_cholmod)
  call test_partners(solver_band)
  call test_partners(solver_cholmod)
  call test_dynamic('stick', 'PLATE Z=0 STICK', 'STOP AT=MAXDEFORMATION')
  call test_dynamic('slip_release', 'PLATE Z=0 SLIP RELEASE=YES', 'STOP AT=SEPARATION')
  call test_summary('test_capacitance')

contains

  !> A reproducible SPD band matrix: random off-diagonals in (-1, 1) inside
  !> the band, diagonal = 1 + the row's absolute sum (diagonally dominant).
  subroutine make_matrix(n, kd, matrix)
    integer, intent(in) :: n, kd
    type(band_matrix_t), intent(out) :: matrix
    real(dp) :: row_sum(n), x
    integer :: i, j
    call band_create(matrix, n, kd)
    row_sum = 0.0_dp
    do j = 1, n
      do i = j + 1, min(n, j + kd)
        x = 2.0_dp*pseudo_random() - 1.0_dp
        matrix%ab(1 + i - j, j) = x
        row_sum(i) = row_sum(i) + abs(x)
        row_sum(j) = row_sum(j) + abs(x)
      end do
    end do
    matrix%ab(1, :) = 1.0_dp + row_sum
  end subroutine make_matrix

  !> A linear congruential sequence in [0, 1) (the same on every machine).
  real(dp) function pseudo_random()
    integer, save :: state = 12345
    state = modulo(1103515245*int(state, kind=8) + 12345_8, 2147483648_8)
    pseudo_random = real(state, dp)/2147483648.0_dp
  end function pseudo_random

  !> Elimination and refactoring: the reference answer.
  function by_elimination(matrix, fixed, values, f) result(u)
    type(band_matrix_t), intent(in) :: matrix
    logical, intent(in) :: fixed(:)
    real(dp), intent(in) :: values(:), f(:)
    real(dp) :: u(size(f))
    type(band_matrix_t) :: factor
    integer :: info
    factor = matrix
    u = f
    call band_constrain(factor, fixed, values, u)
    call band_factor(factor, info)
    call band_solve(factor, u, info)
  end function by_elimination

  !> The capacitance system on the factor of `solver` (band or profile).
  subroutine test_algebra(solver)
    integer, intent(in) :: solver
    integer, parameter :: n = 120, kd = 9
    type(band_matrix_t) :: matrix
    type(factor_t) :: factor
    type(capacitance_t) :: capacitance
    logical :: supports(n), held(n), fixed(n)
    real(dp) :: values(n), f(n), u(n), reference(n), residual(n)
    integer :: i, info, set
    character(:), allocatable :: name
    type(error_t), allocatable :: solve_error
    integer :: solve_status, failed_solves
    name = 'algebra ('//solver_name(solver)//')'
    call make_matrix(n, kd, matrix)
    failed_solves = 0
    do i = 1, n
      f(i) = 2.0_dp*pseudo_random() - 1.0_dp
      values(i) = 0.1_dp*(2.0_dp*pseudo_random() - 1.0_dp)
    end do
    supports = .false.
    supports([1, 2, 57]) = .true.                     ! one support with a non-zero value
    values(1:2) = 0.0_dp
    call factor_compute(factor, matrix, supports, info, solver)
    call check(name//': S~ with supports factors', info == 0)
    call capacitance_reset(capacitance, n)
    do set = 1, 3
      held = .false.
      select case (set)
      case (1)
        held([40, 41, 43]) = .true.                   ! three neighbours in the band
      case (2)
        held([40, 41, 43, 44, 90]) = .true.           ! two more, one far away
      case (3)
        held([41, 43, 44, 90]) = .true.               ! 40 leaves
      end select
      call capacitance_set(capacitance, factor, held, info, solve_error)
      call check(name//' set '//char(48 + set)//': C factors', info == 0)
      u = f
      call band_constrain_rhs(matrix, supports, values, u)
      call factor_solve(factor, u, solve_status)
      failed_solves = failed_solves + merge(1, 0, solve_status /= 0)
      call capacitance_apply(capacitance, values, u)
      fixed = supports .or. held
      reference = by_elimination(matrix, fixed, values, f)
      call check(name//' set '//char(48 + set)//': same solution as refactoring (1e-12)', &
                 maxval(abs(u - reference)) <= 1.0e-12_dp*maxval(abs(reference)))
      call check(name//' set '//char(48 + set)//': held values exact', all(pack(u, held) == pack(values, held)))
      call check(name//' set '//char(48 + set)//': support values', &
                 maxval(abs(pack(u - values, supports))) <= 1.0e-15_dp)
      residual = band_multiply(matrix, u) - f
      call check(name//' set '//char(48 + set)//': free rows in equilibrium', &
                 maxval(abs(pack(residual, .not. fixed))) <= 1.0e-12_dp*maxval(abs(f)))
      call check(name//' set '//char(48 + set)//': lambda = reaction on the held rows', &
                 maxval(abs(pack(residual, held) - capacitance%multiplier)) <= 1.0e-11_dp*maxval(abs(f)))
    end do
    ! Columns: 3 for set 1, 2 more for set 2 (40, 41, 43, 44, 90), none for set 3.
    call check(name//': one back-substitution per equation ever held', capacitance%solves == 5)
    call check(name//': C factored once per set', capacitance%factorizations == 3)
    held = .false.
    held(40) = .true.                                 ! 40 comes back: its column is kept
    call capacitance_set(capacitance, factor, held, info, solve_error)
    call check(name//': a returning equation reuses its column', capacitance%solves == 5)
    call check(name//': every solve returns without error', .not. allocated(solve_error) .and. failed_solves == 0)
  end subroutine test_algebra

  !> Multi-point constraints on the factor of `solver` against a dense KKT solve.
  subroutine test_partners(solver)
    integer, intent(in) :: solver
    integer, parameter :: n = 120, kd = 9, m = 3
    integer, parameter :: held_rows(m) = [40, 41, 43], support_rows(3) = [1, 2, 57]
    type(band_matrix_t) :: matrix
    type(factor_t) :: factor
    type(capacitance_t) :: capacitance
    logical :: supports(n), held(n)
    integer :: partner(2, n), i, j, k, info, rows, lwork
    real(dp) :: weight(2, n), values(n), f(n), u(n), residual(n), expected(n)
    real(dp), allocatable :: kkt(:, :), rhs(:), work(:)
    character(:), allocatable :: name
    type(error_t), allocatable :: solve_error
    integer :: solve_status, failed_solves
    name = 'partners ('//solver_name(solver)//')'
    call make_matrix(n, kd, matrix)
    failed_solves = 0
    do i = 1, n
      f(i) = 2.0_dp*pseudo_random() - 1.0_dp
      values(i) = 0.1_dp*(2.0_dp*pseudo_random() - 1.0_dp)
    end do
    supports = .false.
    supports(support_rows) = .true.
    values(1:2) = 0.0_dp
    partner = 0
    weight = 0.0_dp
    partner(:, 40) = [90, 92]; weight(:, 40) = [0.3_dp, 0.7_dp]
    partner(:, 41) = [92, 94]; weight(:, 41) = [0.6_dp, 0.4_dp]
    held = .false.
    held(held_rows) = .true.                          ! 43: a plain (rigid-plate) equation
    call factor_compute(factor, matrix, supports, info, solver)
    call capacitance_reset(capacitance, n)
    call capacitance_partners(capacitance, partner, weight)
    call capacitance_set(capacitance, factor, held, info, solve_error)
    call check(name//': C factors', info == 0)
    u = f
    call band_constrain_rhs(matrix, supports, values, u)
    call factor_solve(factor, u, solve_status)
    failed_solves = failed_solves + merge(1, 0, solve_status /= 0)
    call check(name//': the solves return without error', .not. allocated(solve_error) .and. failed_solves == 0)
    call capacitance_apply(capacitance, values, u)
    ! The reference: [A  -E; E^T 0] [u; lambda] = [f; values], E's columns the constraints (supports too).
    rows = n + m + size(support_rows)
    allocate(kkt(rows, rows), rhs(rows))
    kkt = 0.0_dp
    do j = 1, n
      do i = j, min(n, j + kd)
        kkt(i, j) = matrix%ab(1 + i - j, j)
        kkt(j, i) = matrix%ab(1 + i - j, j)
      end do
    end do
    rhs(1:n) = f
    do k = 1, m + size(support_rows)
      if (k <= m) then
        i = held_rows(k)
      else
        i = support_rows(k - m)
      end if
      kkt(i, n + k) = -1.0_dp
      kkt(n + k, i) = 1.0_dp
      do j = 1, 2
        if (partner(j, i) == 0) cycle
        kkt(partner(j, i), n + k) = weight(j, i)
        kkt(n + k, partner(j, i)) = -weight(j, i)
      end do
      rhs(n + k) = values(i)
    end do
    lwork = 64*rows
    allocate(work(lwork))
    call dgels('N', rows, rows, 1, kkt, rows, rhs, rows, work, lwork, info)
    call check(name//': the KKT reference solves', info == 0)
    call check(name//': same solution as the KKT solve (1e-10)', &
               maxval(abs(u - rhs(1:n))) <= 1.0e-10_dp*maxval(abs(rhs(1:n))), &
               'difference '//real_text(maxval(abs(u - rhs(1:n)))))
    call check(name//': constraints hold to round-off', &
               abs(u(40) - 0.3_dp*u(90) - 0.7_dp*u(92) - values(40)) <= 1.0e-14_dp*maxval(abs(u)) .and. &
               abs(u(41) - 0.6_dp*u(92) - 0.4_dp*u(94) - values(41)) <= 1.0e-14_dp*maxval(abs(u)) .and. &
               u(43) == values(43))
    residual = band_multiply(matrix, u) - f
    expected = 0.0_dp
    do k = 1, m
      i = held_rows(k)
      expected(i) = capacitance%multiplier(k)
      do j = 1, 2
        if (partner(j, i) > 0) expected(partner(j, i)) = expected(partner(j, i)) - weight(j, i)*capacitance%multiplier(k)
      end do
    end do
    call check(name//': equal and opposite forces (A u - f = lambda on the body, -w lambda on the pad)', &
               maxval(abs(pack(residual - expected, .not. supports))) <= 1.0e-10_dp*maxval(abs(f)))
    call check(name//': lambda matches the KKT multipliers', &
               maxval(abs(capacitance%multiplier - rhs(n + 1:n + m))) <= 1.0e-10_dp*maxval(abs(rhs(n + 1:n + m))))
  end subroutine test_partners

  !> A number as text (for a failed check's detail).
  function real_text(x) result(text)
    real(dp), intent(in) :: x
    character(len=24) :: text
    write(text, '(es12.4)') x
  end function real_text

  !> The Table 1 impact, level 2, both ways.
  subroutine test_dynamic(name, plate, stop_card)
    character(*), intent(in) :: name, plate, stop_card
    type(deck_t) :: deck
    type(record_t) :: fast, slow
    type(error_t), allocatable :: error
    character(:), allocatable :: path
    character(len=12) :: columns(5) = [character(len=12) :: 'alpha_mm', 'force_N', 'q_MPa', 'n_contact', 'uz_cm_m']
    real(dp), allocatable :: a(:), b(:)
    integer :: k
    path = folder//'/'//name//'.inp'
    call write_deck(path, [character(len=80) :: 'ANALYSIS DYNAMIC', 'GEOMETRY AXISYMMETRIC', &
      'MATERIAL apple ELASTIC E=18.11e6 NU=0.219 RHO=756.85', 'MESH SPHERE R=0.0366 LEVEL=2', &
      'INITIAL VZ=-0.9982 AZ=-9.8', 'GRAVITY G=9.8', 'WILSON THETA=1.4', 'TIME DT=1e-5 TEND=5e-3', &
      plate, stop_card, 'END'])
    call read_deck(path, deck, error)
    if (allocated(error)) then
      call check(name//': deck reads', .false., error_text(error)); return
    end if
    call solve_dynamic(deck, fast, error)
    call check(name//': capacitance run', .not. allocated(error))
    if (allocated(error)) return
    call solve_dynamic(deck, slow, error, hold=refactoring_hold_t())
    call check(name//': refactoring run', .not. allocated(error))
    if (allocated(error)) return
    call check(name//': same steps', summary_value(fast, 'steps') == summary_value(slow, 'steps'), &
               summary_value(fast, 'steps')//' vs '//summary_value(slow, 'steps'))
    call check(name//': same contact iterations', &
               summary_value(fast, 'contact_iterations') == summary_value(slow, 'contact_iterations'), &
               summary_value(fast, 'contact_iterations')//' vs '//summary_value(slow, 'contact_iterations'))
    call check(name//': same stop reason', summary_value(fast, 'stop_reason') == summary_value(slow, 'stop_reason'))
    call check(name//': S~ factored once with the capacitance system', summary_value(fast, 'factorizations') == '1', &
               summary_value(fast, 'factorizations'))
    call check(name//': refactoring factors at every contact change', &
               summary_value(slow, 'factorizations') /= '1', summary_value(slow, 'factorizations'))
    print '(a)', name//': factorizations '//summary_value(fast, 'factorizations')//' (capacitance, '// &
      summary_value(fast, 'capacitance_columns')//' columns, '//summary_value(fast, 'capacitance_factorizations')// &
      ' dense factorizations) vs '//summary_value(slow, 'factorizations')//' (refactoring)'
    do k = 1, size(columns)
      a = history_column(fast, trim(columns(k)))
      b = history_column(slow, trim(columns(k)))
      if (size(a) /= size(b) .or. size(a) < 10) then
        call check(name//': '//trim(columns(k))//' rows', .false.); cycle
      end if
      call check(name//': '//trim(columns(k))//' history the same (1e-9 of its largest value)', &
                 maxval(abs(a - b)) <= 1.0e-9_dp*max(maxval(abs(b)), tiny(1.0_dp)))
    end do
    call check_close(name//': alpha_max_mm', summary_real(fast, 'alpha_max_mm'), summary_real(slow, 'alpha_max_mm'), &
                     1.0e-9_dp)
    call check_close(name//': q_max_MPa', summary_real(fast, 'q_max_MPa'), summary_real(slow, 'q_max_MPa'), 1.0e-9_dp)
  end subroutine test_dynamic

  real(dp) function summary_real(record, key) result(value)
    type(record_t), intent(in) :: record
    character(*), intent(in) :: key
    character(:), allocatable :: text
    text = summary_value(record, key)
    read(text, *) value
  end function summary_real
end program test_capacitance
