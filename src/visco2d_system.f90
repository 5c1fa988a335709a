!> Operating-system calls the driver needs (POSIX, through C interoperability):
!> create and rename folders, remove files, process id, terminal test.
module visco2d_system
  use, intrinsic :: iso_c_binding, only: c_int, c_char, c_null_char
  implicit none
  private

  public :: make_directory, rename_path, remove_file, remove_directory, process_id, is_terminal
  public :: directory_exists, remove_tree

  interface
    integer(c_int) function c_mkdir(path, mode) bind(c, name='mkdir')
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: path(*)
      integer(c_int), value :: mode
    end function c_mkdir
    integer(c_int) function c_rename(old, new) bind(c, name='rename')
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: old(*), new(*)
    end function c_rename
    integer(c_int) function c_unlink(path) bind(c, name='unlink')
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: path(*)
    end function c_unlink
    integer(c_int) function c_rmdir(path) bind(c, name='rmdir')
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: path(*)
    end function c_rmdir
    integer(c_int) function c_getpid() bind(c, name='getpid')
      import :: c_int
    end function c_getpid
    integer(c_int) function c_isatty(fd) bind(c, name='isatty')
      import :: c_int
      integer(c_int), value :: fd
    end function c_isatty
  end interface

contains

  !> mkdir -p: create a folder and its missing parents. Returns 0 on success.
  integer function make_directory(path) result(status)
    character(*), intent(in) :: path
    integer :: i
    status = 0
    do i = 2, len(path)
      if (path(i:i) == '/' .and. path(i-1:i-1) /= '/') then
        if (.not. directory_exists(path(1:i-1))) status = c_mkdir(path(1:i-1)//c_null_char, int(o'755', c_int))
      end if
    end do
    if (.not. directory_exists(path)) status = c_mkdir(path//c_null_char, int(o'755', c_int))
    if (directory_exists(path)) status = 0
  end function make_directory

  logical function directory_exists(path)
    character(*), intent(in) :: path
    inquire(file=path//'/.', exist=directory_exists)
  end function directory_exists

  integer function rename_path(old, new) result(status)
    character(*), intent(in) :: old, new
    status = c_rename(old//c_null_char, new//c_null_char)
  end function rename_path

  integer function remove_file(path) result(status)
    character(*), intent(in) :: path
    status = c_unlink(path//c_null_char)
  end function remove_file

  integer function remove_directory(path) result(status)
    character(*), intent(in) :: path
    status = c_rmdir(path//c_null_char)
  end function remove_directory

  !> rm -rf of a folder (used only for an older copy of a case folder).
  subroutine remove_tree(path)
    character(*), intent(in) :: path
    character(:), allocatable :: quoted
    integer :: i, status
    quoted = "'"
    do i = 1, len(path)
      if (path(i:i) == "'") then
        quoted = quoted//"'\''"
      else
        quoted = quoted//path(i:i)
      end if
    end do
    quoted = quoted//"'"
    call execute_command_line('rm -rf -- '//quoted, exitstat=status)
  end subroutine remove_tree

  integer function process_id()
    process_id = int(c_getpid())
  end function process_id

  !> True if the file descriptor (2 = stderr) is a terminal.
  logical function is_terminal(fd)
    integer, intent(in) :: fd
    is_terminal = c_isatty(int(fd, c_int)) == 1
  end function is_terminal
end module visco2d_system
