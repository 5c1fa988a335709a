!> A sparse Cholesky factor of a constrained stiffness (eq. [34]'s S~) by
!> CHOLMOD (SuiteSparse), through C interoperability with the thin C layer
!> visco2d_cholmod_glue.c. The matrix's non-zeros are taken from the band
!> storage; CHOLMOD orders them to reduce fill (AMD or METIS nested
!> dissection, the one with the smaller factor) once per pattern, and
!> factors supernodally with the BLAS: on a 2-D mesh the factor grows as
!> n log n against the band's n^1.5, the factorization as n^1.5 against n^2.
!> Constrained equations keep their entries as explicit zeros, so a new
!> constrained set reuses the ordering.
module visco2d_cholmod
  use, intrinsic :: iso_c_binding, only: c_ptr, c_null_ptr, c_int, c_double, c_associated
  use, intrinsic :: iso_fortran_env, only: int64
  use visco2d_kinds, only: dp
  use visco2d_banded, only: band_matrix_t
  implicit none
  private

  public :: cholmod_factor_t, cholmod_compute, cholmod_solve, cholmod_solve_many, cholmod_entries

  interface
    function visco2d_cholmod_create() bind(c, name='visco2d_cholmod_create') result(handle)
      import :: c_ptr
      type(c_ptr) :: handle
    end function visco2d_cholmod_create
    subroutine visco2d_cholmod_destroy(handle) bind(c, name='visco2d_cholmod_destroy')
      import :: c_ptr
      type(c_ptr), value :: handle
    end subroutine visco2d_cholmod_destroy
    integer(c_int) function visco2d_cholmod_analyze(handle, n, start, rows) bind(c, name='visco2d_cholmod_analyze')
      import :: c_ptr, c_int
      type(c_ptr), value :: handle
      integer(c_int), value :: n
      integer(c_int), intent(in) :: start(*), rows(*)
    end function visco2d_cholmod_analyze
    integer(c_int) function visco2d_cholmod_factor(handle, values, pivot_floor) bind(c, name='visco2d_cholmod_factor')
      import :: c_ptr, c_int, c_double
      type(c_ptr), value :: handle
      real(c_double), intent(in) :: values(*)
      real(c_double), value :: pivot_floor
    end function visco2d_cholmod_factor
    integer(c_int) function visco2d_cholmod_solve(handle, nrhs, b) bind(c, name='visco2d_cholmod_solve')
      import :: c_ptr, c_int, c_double
      type(c_ptr), value :: handle
      integer(c_int), value :: nrhs
      real(c_double), intent(inout) :: b(*)
    end function visco2d_cholmod_solve
    real(c_double) function visco2d_cholmod_entries(handle) bind(c, name='visco2d_cholmod_entries')
      import :: c_ptr, c_double
      type(c_ptr), value :: handle
    end function visco2d_cholmod_entries
  end interface

  !> CHOLMOD's handle and the pattern it was analyzed for (lower triangle by
  !> columns, 0-based rows as CHOLMOD reads them). Not to be copied: the
  !> handle is released when the object goes (final).
  type :: cholmod_factor_t
    type(c_ptr) :: handle = c_null_ptr
    integer :: n = 0
    integer(c_int), allocatable :: start(:)   !< (n + 1) column j's entries: start(j) + 1 .. start(j + 1)
    integer(c_int), allocatable :: rows(:)    !< their rows, 0-based
    real(c_double), allocatable :: values(:)
  contains
    final :: cholmod_release
  end type cholmod_factor_t

contains

  !> Release CHOLMOD's memory.
  subroutine cholmod_release(factor)
    type(cholmod_factor_t), intent(inout) :: factor
    if (c_associated(factor%handle)) call visco2d_cholmod_destroy(factor%handle)
    factor%handle = c_null_ptr
  end subroutine cholmod_release

  !> Factor the band matrix with the equations of `constrained` eliminated
  !> (row and column zeroed, diagonal kept, 1 if it was 0). info: 0 factored;
  !> -1 not positive definite, or a pivot L(j,j)^2 below 1e-13 of its
  !> diagonal, band_factor's test (the caller then finds the equation with
  !> another solver); > 0 CHOLMOD could not run (memory).
  subroutine cholmod_compute(factor, band, constrained, info)
    type(cholmod_factor_t), intent(inout) :: factor
    type(band_matrix_t), intent(in) :: band
    logical, intent(in) :: constrained(:)
    integer, intent(out) :: info
    integer(c_int), allocatable :: start(:), rows(:)
    integer :: i, j, k
    call band_pattern(band, start, rows)
    if (.not. c_associated(factor%handle)) factor%handle = visco2d_cholmod_create()
    if (.not. c_associated(factor%handle)) then
      info = 1
      return
    end if
    if (.not. same_pattern(factor, band%n, start, rows)) then
      factor%n = band%n
      call move_alloc(start, factor%start)
      call move_alloc(rows, factor%rows)
      info = visco2d_cholmod_analyze(factor%handle, int(factor%n, c_int), factor%start, factor%rows)
      if (info /= 0) return
      if (allocated(factor%values)) deallocate(factor%values)
      allocate(factor%values(size(factor%rows)))
    end if
    do j = 1, factor%n
      do k = factor%start(j) + 1, factor%start(j + 1)
        i = factor%rows(k) + 1
        if (i == j) then
          factor%values(k) = band%ab(1, j)
          if (constrained(j) .and. band%ab(1, j) == 0.0_dp) factor%values(k) = 1.0_dp
        else if (constrained(i) .or. constrained(j)) then
          factor%values(k) = 0.0_dp
        else
          factor%values(k) = band%ab(1 + i - j, j)
        end if
      end do
    end do
    info = visco2d_cholmod_factor(factor%handle, factor%values, 1.0e-13_dp)
  end subroutine cholmod_compute

  !> The non-zeros of the band's lower triangle by columns (the diagonal always).
  subroutine band_pattern(band, start, rows)
    type(band_matrix_t), intent(in) :: band
    integer(c_int), allocatable, intent(out) :: start(:), rows(:)
    integer :: i, j, k
    allocate(start(band%n + 1))
    start(1) = 0
    do j = 1, band%n
      k = 1
      do i = j + 1, min(band%n, j + band%kd)
        if (band%ab(1 + i - j, j) /= 0.0_dp) k = k + 1
      end do
      start(j + 1) = start(j) + k
    end do
    allocate(rows(start(band%n + 1)))
    do j = 1, band%n
      k = start(j) + 1
      rows(k) = j - 1
      do i = j + 1, min(band%n, j + band%kd)
        if (band%ab(1 + i - j, j) == 0.0_dp) cycle
        k = k + 1
        rows(k) = i - 1
      end do
    end do
  end subroutine band_pattern

  logical function same_pattern(factor, n, start, rows)
    type(cholmod_factor_t), intent(in) :: factor
    integer, intent(in) :: n
    integer(c_int), intent(in) :: start(:), rows(:)
    same_pattern = .false.
    if (factor%n /= n .or. .not. allocated(factor%start)) return
    if (size(factor%rows) /= size(rows)) return
    same_pattern = all(factor%start == start) .and. all(factor%rows == rows)
  end function same_pattern

  !> Solve A x = b in place. info: 0 solved; 3 no factor; 6 CHOLMOD's solve
  !> failed (out of memory for its workspace); b is then not a solution.
  subroutine cholmod_solve(factor, b, info)
    type(cholmod_factor_t), intent(in) :: factor
    real(dp), intent(inout), contiguous :: b(:)
    integer, intent(out) :: info
    info = 3
    if (.not. c_associated(factor%handle)) return
    info = visco2d_cholmod_solve(factor%handle, 1_c_int, b)
  end subroutine cholmod_solve

  !> Solve A X = B in place (the columns of b); info as cholmod_solve.
  subroutine cholmod_solve_many(factor, b, info)
    type(cholmod_factor_t), intent(in) :: factor
    real(dp), intent(inout), contiguous :: b(:, :)
    integer, intent(out) :: info
    info = 0
    if (size(b, 2) == 0) return
    info = 3
    if (.not. c_associated(factor%handle)) return
    info = visco2d_cholmod_solve(factor%handle, int(size(b, 2), c_int), b)
  end subroutine cholmod_solve_many

  !> The number of reals in the factor.
  integer(int64) function cholmod_entries(factor)
    type(cholmod_factor_t), intent(in) :: factor
    cholmod_entries = 0
    if (c_associated(factor%handle)) cholmod_entries = int(visco2d_cholmod_entries(factor%handle), int64)
  end function cholmod_entries
end module visco2d_cholmod
