!> The Cholesky factor of a constrained stiffness (eq. [25]'s S, eq. [35]'s
!> S~) behind one interface, whatever its storage: `factor_compute` takes the
!> assembled band matrix and the constrained equations (rows and columns
!> zeroed, diagonal kept, as band_constrain_matrix), `factor_solve` and
!> `factor_solve_many` solve with it (eq. [34]). The solver:
!>   solver_cholmod  CHOLMOD (SuiteSparse), sparse supernodal with a
!>                   fill-reducing order (module visco2d_cholmod): the
!>                   default, the fastest measured at mesh levels 1-6
!>                   (doc/study.md, Benchmarks)
!>   solver_profile  envelope storage, Fortran Cholesky and substitutions
!>                   (module visco2d_profile)
!>   solver_band     the legacy band storage and LAPACK dpbtrf/dpbtrs
!>                   (module visco2d_banded): the reference the tests
!>                   compare the others with
!> The deck's SOLVER card chooses one (solver_of_card). All give the same
!> factor up to round-off (the same matrix, other orders of elimination).
module visco2d_factor
  use, intrinsic :: iso_fortran_env, only: int64
  use visco2d_kinds, only: dp
  use visco2d_banded, only: band_matrix_t, band_constrain_matrix, band_factor, band_solve, band_solve_many
  use visco2d_profile, only: profile_matrix_t, profile_from_band, profile_factor, profile_solve, profile_solve_many
  use visco2d_cholmod, only: cholmod_factor_t, cholmod_compute, cholmod_solve, cholmod_solve_many, cholmod_entries
  implicit none
  private

  public :: factor_t, factor_compute, factor_solve, factor_solve_many, factor_entries, solve_failure_text, correction_energy
  public :: solver_none, solver_band, solver_profile, solver_cholmod, solver_default, solver_name, solver_of_card

  !> The solvers, numbered as the SOLVER card's choices (BAND 1, PROFILE 2,
  !> CHOLMOD 3; 0: none given, the default): the factor knows nothing of the
  !> cards, and test_factor checks that the two numberings agree.
  integer, parameter :: solver_none = 0
  integer, parameter :: solver_band = 1          !< band storage, LAPACK dpbtrf/dpbtrs
  integer, parameter :: solver_profile = 2       !< envelope storage (visco2d_profile)
  integer, parameter :: solver_cholmod = 3       !< sparse supernodal, fill-reducing order (visco2d_cholmod)
  integer, parameter :: solver_default = solver_cholmod

  !> factor_solve's info for a factor that was not computed (a program error).
  integer, parameter, public :: solve_unfactored = -1

  !> A factored constrained matrix: the band or the profile factor, as `solver` says.
  type :: factor_t
    integer :: solver = solver_default
    integer :: storage = solver_default         !< the factor in use (CHOLMOD falls back to the profile)
    integer :: n = 0                            !< order
    type(band_matrix_t) :: band                 !< solver_band: the factor in band storage
    type(profile_matrix_t) :: profile           !< solver_profile: the factor in envelope storage
    type(cholmod_factor_t) :: sparse            !< solver_cholmod: CHOLMOD's factor
    logical :: factored = .false.
  end type factor_t

contains

  !> The solver of a SOLVER card (settings%solver of visco2d_model; solver_none: the default).
  pure integer function solver_of_card(card) result(solver)
    integer, intent(in) :: card
    solver = card
    if (card == solver_none) solver = solver_default
  end function solver_of_card

  !> The name of a solver, as a summary or a message writes it.
  pure function solver_name(solver) result(name)
    integer, intent(in) :: solver
    character(:), allocatable :: name
    select case (solver)
    case (solver_band)
      name = 'band'
    case (solver_cholmod)
      name = 'cholmod'
    case default
      name = 'profile'
    end select
  end function solver_name

  !> Factor `matrix` (unfactored, unconstrained; left unchanged) with the
  !> equations of `constrained` eliminated (row and column zeroed, the
  !> diagonal kept, 1 if it was 0). info > 0: equation info has a
  !> non-positive pivot or one below 1e-13 of its diagonal (band_factor).
  !> `solver` (default: the factor's current one) chooses the storage.
  subroutine factor_compute(factor, matrix, constrained, info, solver)
    type(factor_t), intent(inout) :: factor
    type(band_matrix_t), intent(in) :: matrix
    logical, intent(in) :: constrained(:)
    integer, intent(out) :: info
    integer, intent(in), optional :: solver
    if (present(solver)) factor%solver = solver
    factor%n = matrix%n
    factor%storage = factor%solver
    select case (factor%solver)
    case (solver_band)
      factor%band = matrix
      call band_constrain_matrix(factor%band, constrained)
      call band_factor(factor%band, info)
    case (solver_cholmod)
      call cholmod_compute(factor%sparse, matrix, constrained, info)
      if (info /= 0) then                   ! not positive definite, or CHOLMOD failed: the profile
        factor%storage = solver_profile     ! factor finds the equation (or stands in)
        call profile_from_band(matrix, factor%profile, constrained)
        call profile_factor(factor%profile, info)
      end if
    case default
      if (allocated(factor%band%ab)) deallocate(factor%band%ab)
      call profile_from_band(matrix, factor%profile, constrained)
      call profile_factor(factor%profile, info)
    end select
    factor%factored = info == 0
  end subroutine factor_compute

  !> Solve A x = b in place (A the constrained matrix of factor_compute).
  !> info (as factor_compute's, a status the caller turns into its located
  !> error with solve_failure_text): 0 solved; solve_unfactored no factor was
  !> computed; otherwise CHOLMOD's solve failed (visco2d_cholmod_solve's
  !> status: out of memory). b is then not a solution.
  subroutine factor_solve(factor, b, info)
    type(factor_t), intent(in) :: factor
    real(dp), intent(inout), contiguous :: b(:)
    integer, intent(out) :: info
    info = solve_unfactored
    if (.not. factor%factored) return
    info = 0
    select case (factor%storage)
    case (solver_band)
      call band_solve(factor%band, b, info)
      if (info /= 0) info = solve_unfactored
    case (solver_cholmod)
      call cholmod_solve(factor%sparse, b, info)
    case default
      call profile_solve(factor%profile, b, info)
      if (info /= 0) info = solve_unfactored
    end select
  end subroutine factor_solve

  !> Solve A X = B in place for the columns of B, one pass over the factor;
  !> info as factor_solve.
  subroutine factor_solve_many(factor, b, info)
    type(factor_t), intent(in) :: factor
    real(dp), intent(inout), contiguous :: b(:, :)
    integer, intent(out) :: info
    info = solve_unfactored
    if (.not. factor%factored) return
    info = 0
    select case (factor%storage)
    case (solver_band)
      call band_solve_many(factor%band, b, info)
      if (info /= 0) info = solve_unfactored
    case (solver_cholmod)
      call cholmod_solve_many(factor%sparse, b, info)
    case default
      call profile_solve_many(factor%profile, b, info)
      if (info /= 0) info = solve_unfactored
    end select
  end subroutine factor_solve_many

  !> The energy norm of the next Newton correction, |d . r| with d = A^-1 r on
  !> the free equations (r and d zero on the `fixed` ones): the energy test of
  !> the static and quasi-static Newton solves. info as factor_solve.
  subroutine correction_energy(factor, residual, fixed, energy, info)
    type(factor_t), intent(in) :: factor
    real(dp), intent(in) :: residual(:)
    logical, intent(in) :: fixed(:)
    real(dp), intent(out) :: energy
    integer, intent(out) :: info
    real(dp) :: correction(size(residual))
    correction = merge(0.0_dp, residual, fixed)
    energy = 0.0_dp
    call factor_solve(factor, correction, info)
    if (info /= 0) return
    energy = abs(sum(merge(0.0_dp, correction*residual, fixed)))
  end subroutine correction_energy

  !> What a failed factor_solve's info says (for the caller's error).
  pure function solve_failure_text(info) result(text)
    integer, intent(in) :: info
    character(:), allocatable :: text
    character(len=16) :: status
    select case (info)
    case (solve_unfactored)
      text = 'internal error: a solve with a stiffness that was not factored'
      return
    case (3)
      text = 'no factor'
    case (6)
      text = 'out of memory for its workspace'
    case default
      write(status, '(i0)') info
      text = 'status '//trim(status)
    end select
    text = 'the sparse Cholesky solve (CHOLMOD) failed ('//text//'; SOLVER PROFILE solves without CHOLMOD)'
  end function solve_failure_text

  !> The number of reals the factor stores (n (kd + 1) for the band, the
  !> envelope for the profile).
  integer(int64) function factor_entries(factor)
    type(factor_t), intent(in) :: factor
    select case (factor%storage)
    case (solver_band)
      factor_entries = 0
      if (allocated(factor%band%ab)) factor_entries = size(factor%band%ab, kind=int64)
    case (solver_cholmod)
      factor_entries = cholmod_entries(factor%sparse)
    case default
      factor_entries = 0
      if (allocated(factor%profile%values)) factor_entries = size(factor%profile%values, kind=int64)
    end select
  end function factor_entries
end module visco2d_factor
