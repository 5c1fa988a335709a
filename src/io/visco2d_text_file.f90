!> A text file written line by line through C stdio, whose every write and
!> close is checked (the Fortran runtime does not report a write that fails
!> when its buffer is flushed, and then keeps the unit); the file's size is
!> compared with the bytes meant for it. The first failure is kept.
module visco2d_text_file
  use, intrinsic :: iso_fortran_env, only: int64
  use, intrinsic :: iso_c_binding, only: c_ptr, c_null_ptr, c_associated
  use visco2d_strings, only: integer_text
  use visco2d_system, only: file_open_write, file_write, file_close
  implicit none
  private

  public :: text_file_t, text_open, text_put, text_close

  !> A text file written line by line (C stdio: every failed write is
  !> reported); the first failure is kept, later lines are dropped.
  type :: text_file_t
    character(:), allocatable :: path
    type(c_ptr) :: stream = c_null_ptr
    integer(int64) :: bytes = 0            !< bytes meant for the file so far (lines and newlines)
    character(:), allocatable :: message   !< '' or what failed
  end type text_file_t

contains

  !> Create (replace) a text file.
  subroutine text_open(file, path)
    type(text_file_t), intent(out) :: file
    character(*), intent(in) :: path
    file%path = path
    file%message = ''
    file%stream = file_open_write(path)
    if (.not. c_associated(file%stream)) file%message = 'cannot create the file'//open_reason(path)
  end subroutine text_open

  !> ': <why>' of a file that cannot be created, from the Fortran runtime ('' if it can be after all).
  function open_reason(path) result(reason)
    character(*), intent(in) :: path
    character(:), allocatable :: reason
    character(len=256) :: text
    integer :: unit, status
    reason = ''
    open(newunit=unit, file=path, status='replace', action='write', iostat=status, iomsg=text)
    if (status /= 0) then
      reason = ': '//trim(text)
    else
      close(unit, status='delete', iostat=status)
    end if
  end function open_reason

  !> Write one line (nothing after a failure).
  subroutine text_put(file, line)
    type(text_file_t), intent(inout) :: file
    character(*), intent(in) :: line
    if (len(file%message) > 0) return
    if (file_write(file%stream, line) /= 0 .or. file_write(file%stream, new_line('a')) /= 0) then
      file%message = 'writing failed after '//integer_text(file%bytes)//' bytes (disk full or a file size limit?)'
      return
    end if
    file%bytes = file%bytes + len(line) + 1
  end subroutine text_put

  !> Close the file (a failure to write what was still buffered shows here);
  !> then its size must be the bytes written.
  subroutine text_close(file)
    type(text_file_t), intent(inout) :: file
    integer(int64) :: size
    integer :: status
    if (.not. c_associated(file%stream)) return
    status = file_close(file%stream)
    file%stream = c_null_ptr
    if (len(file%message) > 0) return
    if (status /= 0) then
      file%message = 'writing failed when the file was closed (disk full or a file size limit?)'
      return
    end if
    inquire(file=file%path, size=size, iostat=status)
    if (status /= 0 .or. size /= file%bytes) file%message = 'only '//integer_text(max(size, 0_int64))//' of '// &
      integer_text(file%bytes)//' bytes reached the disk (disk full or a file size limit?)'
  end subroutine text_close
end module visco2d_text_file
