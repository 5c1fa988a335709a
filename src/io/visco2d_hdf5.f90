!> A thin HDF5 writer: groups, whole real/integer datasets, string and real
!> attributes. Fortran arrays are written as they are, so an (m, n) array
!> appears as (n, m) in h5py (C order): nodes(2, nnode) reads as (nnode, 2).
!> Every HDF5 call's status is checked: the first failure is kept (with the
!> object being written) and every later call of the writer does nothing;
!> HDF5 prints nothing. The file is built in memory (HDF5's core driver) and
!> its image written to disk by this module at the end: a full disk is then
!> an ordinary failed write, reported, and never a file HDF5 cannot close
!> (HDF5 1.10 crashes in its exit handler on such a file).
module visco2d_hdf5
  use, intrinsic :: iso_c_binding, only: c_ptr, c_null_ptr, c_loc, c_associated
  use, intrinsic :: iso_fortran_env, only: int8, int64
  use hdf5
  use visco2d_kinds, only: dp
  use visco2d_system, only: file_open_write, file_write, file_close
  use visco2d_strings, only: integer_text
  implicit none
  private

  public :: h5_writer_t, h5_open_file, h5_close_file, h5_group, h5_close_group
  public :: h5_write, h5_attribute

  !> An open HDF5 file; `status` becomes non-zero at the first failure,
  !> `failed` says what failed ('' if nothing did).
  type :: h5_writer_t
    integer(hid_t) :: file = -1
    integer :: status = 0
    character(:), allocatable :: failed
    character(:), allocatable :: path       !< where the image goes at h5_close_file
    logical :: library_open = .false.
  end type h5_writer_t

  !> The in-memory file grows by at least this many bytes at a time (more for a
  !> file expected to be larger: h5_open_file's `expected_bytes`).
  integer(size_t), parameter :: minimum_increment = 1048576_size_t

  interface h5_write
    module procedure write_real0, write_real1, write_real2, write_real3, write_integer0, write_integer1, &
                     write_integer2, write_text0
  end interface h5_write

  interface h5_attribute
    module procedure attribute_text, attribute_real
  end interface h5_attribute

contains

  !> Start a file, in memory; h5_close_file writes it to `path` (replacing a
  !> file there), closes every object still open in it and shuts HDF5 down.
  subroutine h5_open_file(writer, path, expected_bytes)
    type(h5_writer_t), intent(out) :: writer
    character(*), intent(in) :: path
    integer(int64), intent(in), optional :: expected_bytes   !< the size the file will have, about (one allocation)
    integer(hid_t) :: access
    integer(size_t) :: increment
    integer :: status
    writer%failed = ''
    writer%path = path
    call h5open_f(status); call check(writer, status, 'the HDF5 library (h5open)')
    if (writer%status /= 0) return
    writer%library_open = .true.
    call h5eset_auto_f(0, status); call check(writer, status, 'the HDF5 error printing (h5eset_auto)')
    call h5pcreate_f(H5P_FILE_ACCESS_F, access, status); call check(writer, status, 'the file access list')
    call h5pset_fclose_degree_f(access, H5F_CLOSE_STRONG_F, status); call check(writer, status, 'the file access list')
    increment = minimum_increment
    if (present(expected_bytes)) increment = int(max(int(minimum_increment, int64), expected_bytes + expected_bytes/8), size_t)
    call h5pset_fapl_core_f(access, increment, .false., status); call check(writer, status, 'the file access list')
    if (writer%status /= 0) return
    call h5fcreate_f(path, H5F_ACC_TRUNC_F, writer%file, status, access_prp=access)
    call check(writer, status, 'the file (h5fcreate)')
    if (status /= 0) writer%file = -1
    call h5pclose_f(access, status); call check(writer, status, 'the file access list')
  end subroutine h5_open_file

  !> Write the file's image to its path (if nothing failed), then close the
  !> file and the library; each status is kept, also after an earlier failure.
  subroutine h5_close_file(writer)
    type(h5_writer_t), intent(inout) :: writer
    integer :: status
    if (writer%status == 0 .and. writer%file >= 0) call write_image(writer)
    if (writer%file >= 0) then
      call h5fclose_f(writer%file, status); call check(writer, status, 'the file (h5fclose)')
    end if
    writer%file = -1
    if (writer%library_open) then
      call h5close_f(status); call check(writer, status, 'the HDF5 library (h5close)')
    end if
    writer%library_open = .false.
  end subroutine h5_close_file

  !> Create a group under `parent` (a file or group id); -1 after a failure.
  function h5_group(writer, parent, name) result(group)
    type(h5_writer_t), intent(inout) :: writer
    integer(hid_t), intent(in) :: parent
    character(*), intent(in) :: name
    integer(hid_t) :: group
    integer :: status
    group = -1
    if (writer%status /= 0) return
    call h5gcreate_f(parent, name, group, status)
    call check(writer, status, 'group '//name)
  end function h5_group

  subroutine h5_close_group(writer, group)
    type(h5_writer_t), intent(inout) :: writer
    integer(hid_t), intent(in) :: group
    integer :: status
    if (writer%status /= 0) return
    call h5gclose_f(group, status)
    call check(writer, status, 'group (h5gclose)')
  end subroutine h5_close_group

  !> The in-memory file to disk (C stdio, every write checked), then the
  !> file's size must be the image's.
  subroutine write_image(writer)
    type(h5_writer_t), intent(inout) :: writer
    integer(int8), allocatable, target :: image(:)
    type(c_ptr) :: buffer
    integer(size_t) :: bytes
    integer(int64) :: size_on_disk
    integer :: status
    type(c_ptr) :: stream
    call h5fflush_f(writer%file, H5F_SCOPE_GLOBAL_F, status); call check(writer, status, 'the file (h5fflush)')
    buffer = c_null_ptr
    call h5fget_file_image_f(writer%file, buffer, 0_size_t, status, bytes)
    call check(writer, status, 'the file image (h5fget_file_image)')
    if (writer%status /= 0) return
    allocate(image(bytes), stat=status)
    if (status /= 0) then
      call fail(writer, status, 'not enough memory for the file image ('//integer_text(int(bytes, int64))//' bytes)')
      return
    end if
    buffer = c_loc(image)
    call h5fget_file_image_f(writer%file, buffer, bytes, status); call check(writer, status, 'the file image')
    if (writer%status /= 0) return
    stream = file_open_write(writer%path)
    if (.not. c_associated(stream)) then
      call fail(writer, -1, 'cannot create the file'); return
    end if
    if (file_write(stream, image) /= 0) call fail(writer, -1, 'writing failed (disk full or a file size limit?)')
    if (file_close(stream) /= 0) call fail(writer, -1, 'writing failed when the file was closed (disk full or a '// &
                                           'file size limit?)')
    if (writer%status /= 0) return
    inquire(file=writer%path, size=size_on_disk, iostat=status)
    if (status /= 0 .or. size_on_disk /= int(bytes, int64)) call fail(writer, -1, 'only '// &
      integer_text(max(size_on_disk, 0_int64))//' of '//integer_text(int(bytes, int64))//' bytes reached the disk '// &
      '(disk full or a file size limit?)')
  end subroutine write_image


  !> Keep the first failure of an HDF5 call and what was being written.
  subroutine check(writer, status, what)
    type(h5_writer_t), intent(inout) :: writer
    integer, intent(in) :: status
    character(*), intent(in) :: what
    if (status /= 0) call fail(writer, status, 'HDF5 failed on '//what//' (status '//integer_text(int(status, int64))//')')
  end subroutine check

  !> Keep the first failure (status /= 0) with its message.
  subroutine fail(writer, status, message)
    type(h5_writer_t), intent(inout) :: writer
    integer, intent(in) :: status
    character(*), intent(in) :: message
    if (writer%status /= 0) return
    writer%status = status
    writer%failed = message
  end subroutine fail

  !> Create a dataset of the given shape and type; returns its id.
  function new_dataset(writer, parent, name, dims, type_id, units) result(dataset)
    type(h5_writer_t), intent(inout) :: writer
    integer(hid_t), intent(in) :: parent, type_id
    character(*), intent(in) :: name
    integer(hsize_t), intent(in) :: dims(:)
    character(*), intent(in), optional :: units
    integer(hid_t) :: dataset, space
    integer :: status
    character(:), allocatable :: what
    dataset = -1
    if (writer%status /= 0) return
    what = 'dataset '//name
    call h5screate_simple_f(size(dims), dims, space, status); call check(writer, status, what)
    call h5dcreate_f(parent, name, type_id, space, dataset, status); call check(writer, status, what)
    call h5sclose_f(space, status); call check(writer, status, what)
    if (present(units)) call attribute_text(writer, dataset, 'units', units)
  end function new_dataset

  !> A scalar double dataset (h5py reads it as a float with `[()]`).
  subroutine write_real0(writer, parent, name, value, units)
    type(h5_writer_t), intent(inout) :: writer
    integer(hid_t), intent(in) :: parent
    character(*), intent(in) :: name
    real(dp), intent(in) :: value
    character(*), intent(in), optional :: units
    integer(hid_t) :: dataset
    integer(hsize_t) :: dims(1) = [1]
    integer :: status
    character(:), allocatable :: what
    if (writer%status /= 0) return
    what = 'dataset '//name
    dataset = new_scalar_dataset(writer, parent, name, H5T_NATIVE_DOUBLE, units)
    call h5dwrite_f(dataset, H5T_NATIVE_DOUBLE, value, dims, status); call check(writer, status, what)
    call h5dclose_f(dataset, status); call check(writer, status, what)
  end subroutine write_real0

  !> A scalar integer dataset.
  subroutine write_integer0(writer, parent, name, value, units)
    type(h5_writer_t), intent(inout) :: writer
    integer(hid_t), intent(in) :: parent
    character(*), intent(in) :: name
    integer, intent(in) :: value
    character(*), intent(in), optional :: units
    integer(hid_t) :: dataset
    integer(hsize_t) :: dims(1) = [1]
    integer :: status
    character(:), allocatable :: what
    if (writer%status /= 0) return
    what = 'dataset '//name
    dataset = new_scalar_dataset(writer, parent, name, H5T_NATIVE_INTEGER, units)
    call h5dwrite_f(dataset, H5T_NATIVE_INTEGER, value, dims, status); call check(writer, status, what)
    call h5dclose_f(dataset, status); call check(writer, status, what)
  end subroutine write_integer0

  !> A scalar fixed-length, null-padded string dataset (h5py reads it as bytes with `[()]`).
  subroutine write_text0(writer, parent, name, text)
    type(h5_writer_t), intent(inout) :: writer
    integer(hid_t), intent(in) :: parent
    character(*), intent(in) :: name, text
    integer(hid_t) :: string_type, dataset
    integer(hsize_t) :: dims(1) = [1]
    integer :: status
    character(:), allocatable :: what
    if (writer%status /= 0) return
    what = 'dataset '//name
    call h5tcopy_f(H5T_C_S1, string_type, status); call check(writer, status, what)
    call h5tset_size_f(string_type, int(max(len(text), 1), size_t), status); call check(writer, status, what)
    call h5tset_strpad_f(string_type, H5T_STR_NULLPAD_F, status); call check(writer, status, what)
    dataset = new_scalar_dataset(writer, parent, name, string_type)
    if (len(text) > 0) then
      call h5dwrite_f(dataset, string_type, text, dims, status)
    else
      call h5dwrite_f(dataset, string_type, ' ', dims, status)
    end if
    call check(writer, status, what)
    call h5dclose_f(dataset, status); call check(writer, status, what)
    call h5tclose_f(string_type, status); call check(writer, status, what)
  end subroutine write_text0

  !> Create a scalar dataset of the given type; returns its id (-1 after a failure).
  function new_scalar_dataset(writer, parent, name, type_id, units) result(dataset)
    type(h5_writer_t), intent(inout) :: writer
    integer(hid_t), intent(in) :: parent, type_id
    character(*), intent(in) :: name
    character(*), intent(in), optional :: units
    integer(hid_t) :: dataset, space
    integer :: status
    character(:), allocatable :: what
    dataset = -1
    if (writer%status /= 0) return
    what = 'dataset '//name
    call h5screate_f(H5S_SCALAR_F, space, status); call check(writer, status, what)
    call h5dcreate_f(parent, name, type_id, space, dataset, status); call check(writer, status, what)
    call h5sclose_f(space, status); call check(writer, status, what)
    if (present(units)) call attribute_text(writer, dataset, 'units', units)
  end function new_scalar_dataset

  subroutine write_real1(writer, parent, name, values, units)
    type(h5_writer_t), intent(inout) :: writer
    integer(hid_t), intent(in) :: parent
    character(*), intent(in) :: name
    real(dp), intent(in) :: values(:)
    character(*), intent(in), optional :: units
    integer(hid_t) :: dataset
    integer(hsize_t) :: dims(1)
    integer :: status
    character(:), allocatable :: what
    if (writer%status /= 0) return
    what = 'dataset '//name
    dims = shape(values, kind=hsize_t)
    dataset = new_dataset(writer, parent, name, dims, H5T_NATIVE_DOUBLE, units)
    call h5dwrite_f(dataset, H5T_NATIVE_DOUBLE, values, dims, status); call check(writer, status, what)
    call h5dclose_f(dataset, status); call check(writer, status, what)
  end subroutine write_real1

  subroutine write_real2(writer, parent, name, values, units)
    type(h5_writer_t), intent(inout) :: writer
    integer(hid_t), intent(in) :: parent
    character(*), intent(in) :: name
    real(dp), intent(in) :: values(:, :)
    character(*), intent(in), optional :: units
    integer(hid_t) :: dataset
    integer(hsize_t) :: dims(2)
    integer :: status
    character(:), allocatable :: what
    if (writer%status /= 0) return
    what = 'dataset '//name
    dims = shape(values, kind=hsize_t)
    dataset = new_dataset(writer, parent, name, dims, H5T_NATIVE_DOUBLE, units)
    call h5dwrite_f(dataset, H5T_NATIVE_DOUBLE, values, dims, status); call check(writer, status, what)
    call h5dclose_f(dataset, status); call check(writer, status, what)
  end subroutine write_real2

  subroutine write_real3(writer, parent, name, values, units)
    type(h5_writer_t), intent(inout) :: writer
    integer(hid_t), intent(in) :: parent
    character(*), intent(in) :: name
    real(dp), intent(in) :: values(:, :, :)
    character(*), intent(in), optional :: units
    integer(hid_t) :: dataset
    integer(hsize_t) :: dims(3)
    integer :: status
    character(:), allocatable :: what
    if (writer%status /= 0) return
    what = 'dataset '//name
    dims = shape(values, kind=hsize_t)
    dataset = new_dataset(writer, parent, name, dims, H5T_NATIVE_DOUBLE, units)
    call h5dwrite_f(dataset, H5T_NATIVE_DOUBLE, values, dims, status); call check(writer, status, what)
    call h5dclose_f(dataset, status); call check(writer, status, what)
  end subroutine write_real3

  subroutine write_integer1(writer, parent, name, values)
    type(h5_writer_t), intent(inout) :: writer
    integer(hid_t), intent(in) :: parent
    character(*), intent(in) :: name
    integer, intent(in) :: values(:)
    integer(hid_t) :: dataset
    integer(hsize_t) :: dims(1)
    integer :: status
    character(:), allocatable :: what
    if (writer%status /= 0) return
    what = 'dataset '//name
    dims = shape(values, kind=hsize_t)
    dataset = new_dataset(writer, parent, name, dims, H5T_NATIVE_INTEGER)
    call h5dwrite_f(dataset, H5T_NATIVE_INTEGER, values, dims, status); call check(writer, status, what)
    call h5dclose_f(dataset, status); call check(writer, status, what)
  end subroutine write_integer1

  subroutine write_integer2(writer, parent, name, values)
    type(h5_writer_t), intent(inout) :: writer
    integer(hid_t), intent(in) :: parent
    character(*), intent(in) :: name
    integer, intent(in) :: values(:, :)
    integer(hid_t) :: dataset
    integer(hsize_t) :: dims(2)
    integer :: status
    character(:), allocatable :: what
    if (writer%status /= 0) return
    what = 'dataset '//name
    dims = shape(values, kind=hsize_t)
    dataset = new_dataset(writer, parent, name, dims, H5T_NATIVE_INTEGER)
    call h5dwrite_f(dataset, H5T_NATIVE_INTEGER, values, dims, status); call check(writer, status, what)
    call h5dclose_f(dataset, status); call check(writer, status, what)
  end subroutine write_integer2

  !> A fixed-length, null-terminated string attribute (h5py reads it as str/bytes).
  subroutine attribute_text(writer, object, name, text)
    type(h5_writer_t), intent(inout) :: writer
    integer(hid_t), intent(in) :: object
    character(*), intent(in) :: name, text
    integer(hid_t) :: string_type, space, attribute
    integer(hsize_t) :: dims(1) = [1]
    integer :: status
    character(:), allocatable :: what
    if (writer%status /= 0) return
    what = 'attribute '//name
    call h5tcopy_f(H5T_C_S1, string_type, status); call check(writer, status, what)
    call h5tset_size_f(string_type, int(max(len(text), 1), size_t), status); call check(writer, status, what)
    call h5tset_strpad_f(string_type, H5T_STR_NULLPAD_F, status); call check(writer, status, what)
    call h5screate_f(H5S_SCALAR_F, space, status); call check(writer, status, what)
    call h5acreate_f(object, name, string_type, space, attribute, status); call check(writer, status, what)
    call h5awrite_f(attribute, string_type, text, dims, status); call check(writer, status, what)
    call h5aclose_f(attribute, status); call check(writer, status, what)
    call h5sclose_f(space, status); call check(writer, status, what)
    call h5tclose_f(string_type, status); call check(writer, status, what)
  end subroutine attribute_text

  !> A scalar double attribute.
  subroutine attribute_real(writer, object, name, value)
    type(h5_writer_t), intent(inout) :: writer
    integer(hid_t), intent(in) :: object
    character(*), intent(in) :: name
    real(dp), intent(in) :: value
    integer(hid_t) :: space, attribute
    integer(hsize_t) :: dims(1) = [1]
    integer :: status
    character(:), allocatable :: what
    if (writer%status /= 0) return
    what = 'attribute '//name
    call h5screate_f(H5S_SCALAR_F, space, status); call check(writer, status, what)
    call h5acreate_f(object, name, H5T_NATIVE_DOUBLE, space, attribute, status); call check(writer, status, what)
    call h5awrite_f(attribute, H5T_NATIVE_DOUBLE, value, dims, status); call check(writer, status, what)
    call h5aclose_f(attribute, status); call check(writer, status, what)
    call h5sclose_f(space, status); call check(writer, status, what)
  end subroutine attribute_real
end module visco2d_hdf5
