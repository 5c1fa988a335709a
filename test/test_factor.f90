!> The profile (envelope) Cholesky of visco2d_profile and CHOLMOD's against the band
!> Cholesky of visco2d_banded (LAPACK dpbtrf/dpbtrs) and a dense one
!> (LAPACK dpotrf/dpotrs), through visco2d_factor:
!>
!>  1. Random SPD matrices in band storage whose rows start at random
!>     columns inside the band (so the envelope is a strict part of the
!>     band), some equations constrained (rows and columns eliminated),
!>     several sizes and condition numbers. Tolerances from the error
!>     analysis of Cholesky (Higham, Accuracy and Stability of Numerical
!>     Algorithms, 2nd ed., Thms. 10.3-10.4): the computed x solves
!>     (A + dA) x = b with |dA| <= gamma_(w+1) |L| |L^T|, w the widest row
!>     of the envelope, gamma_k = k u / (1 - k u), u the unit round-off;
!>     for SPD A, || |L| |L^T| ||_2 <= n ||A||_2. So the backward error
!>     ||b - A x|| / (||A|| ||x||) is below n gamma_(w+1) whatever the
!>     conditioning (checked for each solver), and two solvers' x differ by
!>     at most twice the forward bound 2 n gamma_(w+1) kappa_2(A) relative
!>     (checked between profile, band and dense; kappa_2 from the dense
!>     eigenvalues, LAPACK dsyev). The factors themselves (L of the profile
!>     and of the band) agree to the same bound.
!>  2. The real S~ of eq. [35] (Table 1 impact, sphere level 2, Wilson-theta
!>     at DT = 0.01 ms) with its supports, the same comparisons, and a
!>     multi-right-hand-side solve equal to the single ones.
!>  3. A singular matrix (a zero row left free): every solver reports the
!>     same equation.
!> CHOLMOD (visco2d_cholmod) is checked against dense and band too, with the
!> same bounds for n in place of w + 1 (its ordering is its own).
program test_factor
  use, intrinsic :: iso_fortran_env, only: int64
  use visco2d_kinds, only: dp
  use visco2d_lapack, only: dpotrf, dpotrs, dsyev
  use visco2d_error, only: error_t, error_text, set_error, locate_error
  use visco2d_banded, only: band_matrix_t, band_create, band_multiply, band_constrain_rhs
  use visco2d_factor, only: factor_t, factor_compute, factor_solve, factor_solve_many, factor_entries, &
                            solver_band, solver_profile, solver_cholmod, solver_name, solver_none, &
                            solve_unfactored, solve_failure_text
  use visco2d_deck_types, only: solver_card_default, solver_card_band, solver_card_profile, solver_card_cholmod
  use visco2d_deck, only: deck_t, read_deck
  use visco2d_time_step, only: stepper_t, stepper_create, effective_stiffness
  use visco2d_testing, only: check, test_summary, write_deck, check_text_contains
  use visco2d_record, only: record_t
  use visco2d_driver, only: run_deck
  use visco2d_expect, only: summary_value
  implicit none

  real(dp), parameter :: unit_roundoff = epsilon(1.0_dp)/2.0_dp
  character(*), parameter :: folder = 'build/test-tmp/test_factor'

  call execute_command_line('mkdir -p '//folder)
  call test_random('random n=60 kd=7 shift=1', 60, 7, 1.0_dp)
  call test_random('random n=200 kd=25 shift=1', 200, 25, 1.0_dp)
  call test_random('random n=300 kd=40 shift=1e-6', 300, 40, 1.0e-6_dp)
  call test_random('random n=400 kd=30 shift=1e-9, nothing constrained', 400, 30, 1.0e-9_dp, .false.)
  call test_assembled()
  call test_singular()
  call test_solver_card()
  call test_solve_errors()
  ! The factor numbers its solvers as the SOLVER card does, without using the cards.
  call check('the factor and the SOLVER card number the solvers alike', solver_none == solver_card_default .and. &
             solver_band == solver_card_band .and. solver_profile == solver_card_profile .and. &
             solver_cholmod == solver_card_cholmod)
  call test_summary('test_factor')

contains

  !> A solve that cannot be done returns a status (the caller's error, which
  !> the time loop or the driver locates at the deck and step), never stops
  !> the process: no factor computed, and a CHOLMOD factor without CHOLMOD's
  !> handle (its solve's 'no factor' status, 3).
  subroutine test_solve_errors()
    type(factor_t) :: unfactored, no_handle
    type(error_t), allocatable :: error
    real(dp) :: x(4), many(4, 2)
    integer :: status
    x = 1.0_dp
    many = 1.0_dp
    call factor_solve(unfactored, x, status)
    call check('solve_unfactored_is_a_status', status == solve_unfactored)
    call check_text_contains('solve_unfactored_says_so', solve_failure_text(status), 'not factored')
    call factor_solve_many(unfactored, many, status)
    call check('solve_many_unfactored_is_a_status', status == solve_unfactored)
    no_handle%storage = solver_cholmod
    no_handle%factored = .true.
    no_handle%n = 4
    call factor_solve(no_handle, x, status)
    call check('cholmod_solve_failure_is_a_status', status == 3)
    call check_text_contains('cholmod_solve_failure_says_so', solve_failure_text(status), &
                             'the sparse Cholesky solve (CHOLMOD) failed (no factor;')
    call factor_solve_many(no_handle, many, status)
    call check('cholmod_solve_many_failure_is_a_status', status == 3)
    call set_error(error, solve_failure_text(3))                       ! as the solvers do
    call locate_error(error, 'drop.inp', 7, 'TIME', ' at step 12 (t = 1.2000E-04 s)')   ! as the time loop does
    call check('solve_failure_located_at_deck_and_step', error_text(error) == 'drop.inp:7: TIME: the sparse '// &
               'Cholesky solve (CHOLMOD) failed (no factor; SOLVER PROFILE solves without CHOLMOD) at step 12 '// &
               '(t = 1.2000E-04 s)', error_text(error))
    call locate_error(error, 'other.inp')
    call check('located_error_kept', error%file == 'drop.inp' .and. error%line == 7, error_text(error))
  end subroutine test_solve_errors

  !> A linear congruential sequence in [0, 1) (the same on every machine).
  real(dp) function pseudo_random()
    integer, save :: state = 2024
    state = int(modulo(1103515245*int(state, int64) + 12345_int64, 2147483648_int64))
    pseudo_random = real(state, dp)/2147483648.0_dp
  end function pseudo_random

  !> An SPD band matrix: row i non-zero from a random column within the band
  !> to the diagonal, off-diagonals in (-1, 0), diagonal = the row's
  !> absolute sum + shift: a weighted graph Laplacian (singular: its
  !> smallest eigenvalue is 0) shifted by `shift`, so that kappa_2 grows as
  !> 1/shift (shift = 1: well conditioned; 1e-6: kappa ~ 1e7 before the
  !> constrained equations raise the smallest eigenvalue).
  subroutine make_matrix(n, kd, shift, matrix)
    integer, intent(in) :: n, kd
    real(dp), intent(in) :: shift
    type(band_matrix_t), intent(out) :: matrix
    real(dp) :: row_sum(n), x
    integer :: i, j, first
    call band_create(matrix, n, kd)
    row_sum = 0.0_dp
    do i = 2, n
      first = max(1, i - 1 - int(pseudo_random()*kd))
      do j = first, i - 1
        x = -pseudo_random()
        matrix%ab(1 + i - j, j) = x
        row_sum(i) = row_sum(i) + abs(x)
        row_sum(j) = row_sum(j) + abs(x)
      end do
    end do
    matrix%ab(1, :) = row_sum + shift
  end subroutine make_matrix

  !> The constrained matrix (rows and columns of `fixed` zeroed, diagonal
  !> kept) as a dense symmetric matrix.
  function dense_of(matrix, fixed) result(a)
    type(band_matrix_t), intent(in) :: matrix
    logical, intent(in) :: fixed(:)
    real(dp) :: a(matrix%n, matrix%n)
    integer :: i, j
    a = 0.0_dp
    do j = 1, matrix%n
      do i = j, min(matrix%n, j + matrix%kd)
        if (i /= j .and. (fixed(i) .or. fixed(j))) cycle
        a(i, j) = matrix%ab(1 + i - j, j)
        a(j, i) = a(i, j)
      end do
    end do
  end function dense_of

  !> kappa_2 of a dense SPD matrix from its eigenvalues.
  real(dp) function condition_number(a) result(kappa)
    real(dp), intent(in) :: a(:, :)
    real(dp) :: copy(size(a, 1), size(a, 1)), eigenvalues(size(a, 1)), query(1)
    real(dp), allocatable :: space(:)
    integer :: n, info
    n = size(a, 1)
    copy = a
    call dsyev('N', 'L', n, copy, n, eigenvalues, query, -1, info)
    allocate(space(int(query(1))))
    call dsyev('N', 'L', n, copy, n, eigenvalues, space, size(space), info)
    kappa = eigenvalues(n)/eigenvalues(1)
  end function condition_number

  !> The widest row of the factor's envelope (w: a row couples to at most w earlier equations).
  integer function widest_row(factor)
    type(factor_t), intent(in) :: factor
    integer :: i
    widest_row = 0
    do i = 1, factor%profile%n
      widest_row = max(widest_row, i - factor%profile%first(i))
    end do
  end function widest_row

  real(dp) function gamma(k)
    integer, intent(in) :: k
    gamma = k*unit_roundoff/(1.0_dp - k*unit_roundoff)
  end function gamma

  !> Backward error ||b - A x||_inf / (||A||_inf ||x||_inf) of x for the
  !> constrained dense matrix a.
  real(dp) function backward_error(a, x, b)
    real(dp), intent(in) :: a(:, :), x(:), b(:)
    backward_error = maxval(abs(b - matmul(a, x)))/(maxval(sum(abs(a), dim=1))*maxval(abs(x)))
  end function backward_error

  !> The comparisons of part 1 and 2 for one constrained matrix.
  subroutine compare_solvers(name, matrix, fixed)
    character(*), intent(in) :: name
    type(band_matrix_t), intent(in) :: matrix
    logical, intent(in) :: fixed(:)
    type(factor_t) :: band, profile, sparse
    real(dp), allocatable :: a(:, :), dense(:, :), b(:), x_band(:), x_profile(:), x_dense(:), x_sparse(:), many(:, :)
    real(dp) :: kappa, backward_bound, forward_bound, scale, l_band, l_profile, factor_difference, sparse_backward
    integer :: info_band, info_profile, info_sparse, info, n, i, j, k, w
    character(len=200) :: detail
    integer :: solve_status, failed_solves
    n = matrix%n
    call factor_compute(band, matrix, fixed, info_band, solver_band)
    call factor_compute(profile, matrix, fixed, info_profile, solver_profile)
    call check(name//': band factors', info_band == 0)
    call check(name//': profile factors', info_profile == 0)
    call factor_compute(sparse, matrix, fixed, info_sparse, solver_cholmod)
    call check(name//': CHOLMOD factors (not through the profile fallback)', &
               info_sparse == 0 .and. sparse%storage == solver_cholmod)
    if (info_band /= 0 .or. info_profile /= 0 .or. info_sparse /= 0) return
    call check(name//': the envelope is smaller than the band', factor_entries(profile) < factor_entries(band))
    a = dense_of(matrix, fixed)
    kappa = condition_number(a)
    w = widest_row(profile)
    backward_bound = n*gamma(w + 1)
    forward_bound = 2.0_dp*backward_bound*kappa
    write(detail, '(a, i0, a, i0, a, es9.2, a, es9.2)') 'n ', n, ', w ', w, ', kappa ', kappa, ', bound ', forward_bound
    print '(a)', name//': '//trim(detail)//', band '//itoa64(factor_entries(band))//' reals, profile '// &
      itoa64(factor_entries(profile))

    ! The factors: L(i, j) of the profile against the band's ab(1 + i - j, j).
    factor_difference = 0.0_dp
    scale = 0.0_dp
    do i = 1, n
      do j = max(1, i - matrix%kd), i
        l_band = band%band%ab(1 + i - j, j)
        l_profile = 0.0_dp
        if (j >= profile%profile%first(i)) l_profile = profile%profile%values(profile%profile%start(i) + j - &
                                                                             profile%profile%first(i))
        factor_difference = max(factor_difference, abs(l_band - l_profile))
        scale = max(scale, abs(l_band))
      end do
    end do
    call check(name//': the same factor L (to 2 n gamma_(w+1) kappa)', factor_difference <= forward_bound*scale, &
               real_text(factor_difference/scale)//' > '//real_text(forward_bound))

    allocate(b(n))
    do i = 1, n
      b(i) = 2.0_dp*pseudo_random() - 1.0_dp
    end do
    b = merge(0.0_dp, b, fixed)
    failed_solves = 0
    x_band = b
    call factor_solve(band, x_band, solve_status)
    failed_solves = failed_solves + merge(1, 0, solve_status /= 0)
    x_profile = b
    call factor_solve(profile, x_profile, solve_status)
    failed_solves = failed_solves + merge(1, 0, solve_status /= 0)
    dense = a
    call dpotrf('L', n, dense, n, info)
    call check(name//': dense dpotrf factors', info == 0)
    x_dense = b
    call dpotrs('L', n, 1, dense, n, x_dense, n, info)
    call check(name//': band backward error below n gamma_(w+1)', backward_error(a, x_band, b) <= backward_bound, &
               real_text(backward_error(a, x_band, b))//' > '//real_text(backward_bound))
    call check(name//': profile backward error below n gamma_(w+1)', &
               backward_error(a, x_profile, b) <= backward_bound, &
               real_text(backward_error(a, x_profile, b))//' > '//real_text(backward_bound))
    call check(name//': profile = band (to 2 n gamma_(w+1) kappa)', &
               maxval(abs(x_profile - x_band)) <= forward_bound*maxval(abs(x_band)), &
               real_text(maxval(abs(x_profile - x_band))/maxval(abs(x_band)))//' > '//real_text(forward_bound))
    call check(name//': profile = dense dpotrf (to 2 n gamma_(w+1) kappa)', &
               maxval(abs(x_profile - x_dense)) <= forward_bound*maxval(abs(x_dense)), &
               real_text(maxval(abs(x_profile - x_dense))/maxval(abs(x_dense)))//' > '//real_text(forward_bound))

    ! CHOLMOD: another order of elimination, so its rows of L hold up to n
    ! entries: the bounds with n in place of w + 1.
    x_sparse = b
    call factor_solve(sparse, x_sparse, solve_status)
    failed_solves = failed_solves + merge(1, 0, solve_status /= 0)
    sparse_backward = n*gamma(n + 1)
    call check(name//': CHOLMOD backward error below n gamma_(n+1)', backward_error(a, x_sparse, b) <= sparse_backward, &
               real_text(backward_error(a, x_sparse, b))//' > '//real_text(sparse_backward))
    call check(name//': CHOLMOD = dense dpotrf (to 2 n gamma_(n+1) kappa)', &
               maxval(abs(x_sparse - x_dense)) <= 2.0_dp*sparse_backward*kappa*maxval(abs(x_dense)), &
               real_text(maxval(abs(x_sparse - x_dense))/maxval(abs(x_dense)))//' > '// &
               real_text(2.0_dp*sparse_backward*kappa))
    call check(name//': CHOLMOD = band (to 2 n gamma_(n+1) kappa)', &
               maxval(abs(x_sparse - x_band)) <= 2.0_dp*sparse_backward*kappa*maxval(abs(x_band)))
    print '(a)', name//': CHOLMOD factor '//itoa64(factor_entries(sparse))//' reals; |x - x_dense|/|x|: band '// &
      real_text(maxval(abs(x_band - x_dense))/maxval(abs(x_dense)))//', profile '// &
      real_text(maxval(abs(x_profile - x_dense))/maxval(abs(x_dense)))//', CHOLMOD '// &
      real_text(maxval(abs(x_sparse - x_dense))/maxval(abs(x_dense)))

    ! Several right-hand sides at once: each column as its single solve (the
    ! same operations on each column, in another order: the backward bound).
    allocate(many(n, 3))
    do k = 1, 3
      many(:, k) = b*k + merge(0.0_dp, 1.0_dp, fixed)*(k - 1)
    end do
    x_dense = many(:, 3)
    call factor_solve_many(profile, many, solve_status)
    failed_solves = failed_solves + merge(1, 0, solve_status /= 0)
    call factor_solve(profile, x_dense, solve_status)
    call check(name//': profile, three right-hand sides at once = one at a time', &
               maxval(abs(many(:, 3) - x_dense)) <= forward_bound*maxval(abs(x_dense)))
    many(:, 1) = b
    call factor_solve_many(band, many(:, 1:1), solve_status)
    failed_solves = failed_solves + merge(1, 0, solve_status /= 0)
    call check(name//': band, one column through solve_many = solve', all(many(:, 1) == x_band))
    many(:, 1) = b
    many(:, 2) = 2.0_dp*b
    call factor_solve_many(sparse, many(:, 1:2), solve_status)
    failed_solves = failed_solves + merge(1, 0, solve_status /= 0)
    call check(name//': CHOLMOD, two columns at once = one at a time (to 2 n gamma_(n+1) kappa)', &
               maxval(abs(many(:, 1) - x_sparse)) <= 2.0_dp*sparse_backward*kappa*maxval(abs(x_sparse)) .and. &
               maxval(abs(many(:, 2) - 2.0_dp*x_sparse)) <= 4.0_dp*sparse_backward*kappa*maxval(abs(x_sparse)))
    call check(name//': every solve returns without error', failed_solves == 0)
  end subroutine compare_solvers

  !> Part 1: random envelopes, some equations constrained.
  subroutine test_random(name, n, kd, shift, constrain)
    character(*), intent(in) :: name
    integer, intent(in) :: n, kd
    real(dp), intent(in) :: shift
    logical, intent(in), optional :: constrain
    type(band_matrix_t) :: matrix
    logical :: fixed(n)
    integer :: i
    call make_matrix(n, kd, shift, matrix)
    fixed = .false.
    do i = 1, n
      fixed(i) = pseudo_random() < 0.05_dp
    end do
    if (present(constrain)) then
      if (.not. constrain) fixed = .false.
    end if
    call compare_solvers(name, matrix, fixed)
  end subroutine test_random

  !> Part 2: S~ of the Table 1 impact on the level-2 sphere, with its supports.
  subroutine test_assembled()
    type(deck_t) :: deck
    type(stepper_t) :: stepper
    type(error_t), allocatable :: error
    real(dp), allocatable :: rows(:)
    character(:), allocatable :: path
    path = folder//'/table1_level2.inp'
    call write_deck(path, [character(len=80) :: 'ANALYSIS DYNAMIC', 'GEOMETRY AXISYMMETRIC', &
      'MATERIAL apple ELASTIC E=18.11e6 NU=0.219 RHO=756.85', 'MESH SPHERE R=0.0366 LEVEL=2', &
      'INITIAL VZ=-0.9982', 'WILSON THETA=1.4', 'TIME DT=1e-5 TEND=1e-3', 'PLATE Z=0 STICK', 'END'])
    call read_deck(path, deck, error)
    call check('assembled: deck reads', .not. allocated(error))
    if (allocated(error)) then
      print '(a)', error_text(error)
      return
    end if
    call stepper_create(deck, .false., stepper)
    allocate(rows(2*deck%mesh%nnode))
    call effective_stiffness(stepper, deck, 1, 1.0e-5_dp, rows)
    call compare_solvers('assembled S~ (level 2, supports)', stepper%points(1)%effective, stepper%supports)
  end subroutine test_assembled

  !> Part 3: equation 7 has no stiffness and no support: both report it.
  subroutine test_singular()
    type(band_matrix_t) :: matrix
    type(factor_t) :: band, profile, sparse
    logical :: fixed(40)
    integer :: info_band, info_profile, info_sparse, j
    call make_matrix(40, 5, 1.0_dp, matrix)
    do j = max(1, 7 - 5), 7
      matrix%ab(1 + 7 - j, j) = 0.0_dp                 ! row 7, left of and on the diagonal
    end do
    matrix%ab(:, 7) = 0.0_dp                           ! column 7 below the diagonal
    fixed = .false.
    call factor_compute(band, matrix, fixed, info_band, solver_band)
    call factor_compute(profile, matrix, fixed, info_profile, solver_profile)
    call check('singular: band reports equation 7', info_band == 7)
    call check('singular: profile reports equation 7', info_profile == 7)
    call factor_compute(sparse, matrix, fixed, info_sparse, solver_cholmod)
    call check('singular: CHOLMOD reports equation 7 (found by the profile factor)', info_sparse == 7)
    fixed(7) = .true.
    call factor_compute(profile, matrix, fixed, info_profile, solver_profile)
    call check('singular: constrained, it factors (diagonal 1)', info_profile == 0)
  end subroutine test_singular

  function real_text(x) result(text)
    real(dp), intent(in) :: x
    character(:), allocatable :: text
    character(len=24) :: buffer
    write(buffer, '(es10.3)') x
    text = trim(adjustl(buffer))
  end function real_text

  function itoa64(i) result(text)
    integer(int64), intent(in) :: i
    character(:), allocatable :: text
    character(len=24) :: buffer
    write(buffer, '(i0)') i
    text = trim(buffer)
  end function itoa64
  !> The SOLVER card: the paper's Table 1 impact (inputs/table1_elastic.inp)
  !> with SOLVER BAND (the legacy LAPACK path), PROFILE and CHOLMOD gives the
  !> default run's alpha, t and q. The systems are the same; their solutions
  !> differ by round-off (condition number ~1e4 at level 1: ~1e-12), and the
  !> contact events, decided on the same side of the plate, are the same, so
  !> 1e-9 relative is a bound with room for the round-off, far below any
  !> physical change.
  subroutine test_solver_card()
    character(len=*), parameter :: names(3) = ['BAND   ', 'PROFILE', 'CHOLMOD']
    character(len=*), parameter :: keys(4) = ['alpha_max_mm  ', 't_alpha_max_ms', 'q_max_MPa     ', 'steps         ']
    character(len=200), allocatable :: lines(:)
    character(len=200) :: line
    type(record_t) :: record
    type(error_t), allocatable :: error
    real(dp) :: reference(4), value
    integer :: unit, ios, k, j, n
    character(:), allocatable :: path, text
    open(newunit=unit, file='inputs/table1_elastic.inp', status='old', action='read', iostat=ios)
    call check('SOLVER card: inputs/table1_elastic.inp readable', ios == 0)
    if (ios /= 0) return
    allocate(lines(0))
    do
      read(unit, '(a)', iostat=ios) line
      if (ios /= 0) exit
      lines = [character(len=200) :: lines, line]
    end do
    close(unit)
    n = size(lines)
    call write_deck(folder//'/table1_default.inp', lines)
    call run_deck(folder//'/table1_default.inp', folder//'/out', record, error)
    call check('SOLVER card: the default run', .not. allocated(error))
    if (allocated(error)) return
    do j = 1, size(keys)
      text = summary_value(record, trim(keys(j)))
      read(text, *) reference(j)
    end do
    do k = 1, size(names)
      path = folder//'/table1_'//trim(names(k))//'.inp'
      call write_deck(path, [character(len=200) :: lines(:n - 1), 'SOLVER '//trim(names(k)), lines(n:)])
      call run_deck(path, folder//'/out', record, error)
      call check('SOLVER '//trim(names(k))//': runs', .not. allocated(error))
      if (allocated(error)) cycle
      call check('SOLVER '//trim(names(k))//': the summary names it', summary_value(record, 'solver') == trim(names(k)))
      do j = 1, size(keys)
        text = summary_value(record, trim(keys(j)))
        read(text, *) value
        call check('SOLVER '//trim(names(k))//': '//trim(keys(j))//' equals the default run''s to 1e-9', &
                   abs(value - reference(j)) <= 1.0e-9_dp*abs(reference(j)))
      end do
    end do
  end subroutine test_solver_card

end program test_factor
