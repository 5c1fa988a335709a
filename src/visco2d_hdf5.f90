!> A thin HDF5 writer: groups, whole real/integer datasets, string and real
!> attributes. Fortran arrays are written as they are, so an (m, n) array
!> appears as (n, m) in h5py (C order): nodes(2, nnode) reads as (nnode, 2).
module visco2d_hdf5
  use hdf5
  use visco2d_kinds, only: dp
  implicit none
  private

  public :: h5_writer_t, h5_open_file, h5_close_file, h5_group, h5_close_group
  public :: h5_write, h5_attribute

  !> An open HDF5 file; `status` becomes non-zero at the first failed call.
  type :: h5_writer_t
    integer(hid_t) :: file = -1
    integer :: status = 0
  end type h5_writer_t

  interface h5_write
    module procedure write_real1, write_real2, write_real3, write_integer1, write_integer2
  end interface h5_write

  interface h5_attribute
    module procedure attribute_text, attribute_real
  end interface h5_attribute

contains

  !> Create (truncate) a file.
  subroutine h5_open_file(writer, path)
    type(h5_writer_t), intent(out) :: writer
    character(*), intent(in) :: path
    integer :: status
    call h5open_f(status)
    call h5eset_auto_f(0, status)               ! errors come back as status codes, not prints
    call h5fcreate_f(path, H5F_ACC_TRUNC_F, writer%file, writer%status)
  end subroutine h5_open_file

  subroutine h5_close_file(writer)
    type(h5_writer_t), intent(inout) :: writer
    integer :: status
    status = 0
    if (writer%file >= 0) call h5fclose_f(writer%file, status)
    if (status /= 0) writer%status = status
    writer%file = -1
  end subroutine h5_close_file

  !> Create a group under `parent` (a file or group id).
  function h5_group(writer, parent, name) result(group)
    type(h5_writer_t), intent(inout) :: writer
    integer(hid_t), intent(in) :: parent
    character(*), intent(in) :: name
    integer(hid_t) :: group
    integer :: status
    call h5gcreate_f(parent, name, group, status)
    call check(writer, status)
  end function h5_group

  subroutine h5_close_group(writer, group)
    type(h5_writer_t), intent(inout) :: writer
    integer(hid_t), intent(in) :: group
    integer :: status
    call h5gclose_f(group, status)
    call check(writer, status)
  end subroutine h5_close_group

  subroutine check(writer, status)
    type(h5_writer_t), intent(inout) :: writer
    integer, intent(in) :: status
    if (status /= 0 .and. writer%status == 0) writer%status = status
  end subroutine check

  !> Create a dataset of the given shape and type; returns its id.
  function new_dataset(writer, parent, name, dims, type_id, units) result(dataset)
    type(h5_writer_t), intent(inout) :: writer
    integer(hid_t), intent(in) :: parent, type_id
    character(*), intent(in) :: name
    integer(hsize_t), intent(in) :: dims(:)
    character(*), intent(in), optional :: units
    integer(hid_t) :: dataset, space
    integer :: status
    call h5screate_simple_f(size(dims), dims, space, status); call check(writer, status)
    call h5dcreate_f(parent, name, type_id, space, dataset, status); call check(writer, status)
    call h5sclose_f(space, status); call check(writer, status)
    if (present(units)) call attribute_text(writer, dataset, 'units', units)
  end function new_dataset

  subroutine write_real1(writer, parent, name, values, units)
    type(h5_writer_t), intent(inout) :: writer
    integer(hid_t), intent(in) :: parent
    character(*), intent(in) :: name
    real(dp), intent(in) :: values(:)
    character(*), intent(in), optional :: units
    integer(hid_t) :: dataset
    integer(hsize_t) :: dims(1)
    integer :: status
    dims = shape(values, kind=hsize_t)
    dataset = new_dataset(writer, parent, name, dims, H5T_NATIVE_DOUBLE, units)
    call h5dwrite_f(dataset, H5T_NATIVE_DOUBLE, values, dims, status); call check(writer, status)
    call h5dclose_f(dataset, status); call check(writer, status)
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
    dims = shape(values, kind=hsize_t)
    dataset = new_dataset(writer, parent, name, dims, H5T_NATIVE_DOUBLE, units)
    call h5dwrite_f(dataset, H5T_NATIVE_DOUBLE, values, dims, status); call check(writer, status)
    call h5dclose_f(dataset, status); call check(writer, status)
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
    dims = shape(values, kind=hsize_t)
    dataset = new_dataset(writer, parent, name, dims, H5T_NATIVE_DOUBLE, units)
    call h5dwrite_f(dataset, H5T_NATIVE_DOUBLE, values, dims, status); call check(writer, status)
    call h5dclose_f(dataset, status); call check(writer, status)
  end subroutine write_real3

  subroutine write_integer1(writer, parent, name, values)
    type(h5_writer_t), intent(inout) :: writer
    integer(hid_t), intent(in) :: parent
    character(*), intent(in) :: name
    integer, intent(in) :: values(:)
    integer(hid_t) :: dataset
    integer(hsize_t) :: dims(1)
    integer :: status
    dims = shape(values, kind=hsize_t)
    dataset = new_dataset(writer, parent, name, dims, H5T_NATIVE_INTEGER)
    call h5dwrite_f(dataset, H5T_NATIVE_INTEGER, values, dims, status); call check(writer, status)
    call h5dclose_f(dataset, status); call check(writer, status)
  end subroutine write_integer1

  subroutine write_integer2(writer, parent, name, values)
    type(h5_writer_t), intent(inout) :: writer
    integer(hid_t), intent(in) :: parent
    character(*), intent(in) :: name
    integer, intent(in) :: values(:, :)
    integer(hid_t) :: dataset
    integer(hsize_t) :: dims(2)
    integer :: status
    dims = shape(values, kind=hsize_t)
    dataset = new_dataset(writer, parent, name, dims, H5T_NATIVE_INTEGER)
    call h5dwrite_f(dataset, H5T_NATIVE_INTEGER, values, dims, status); call check(writer, status)
    call h5dclose_f(dataset, status); call check(writer, status)
  end subroutine write_integer2

  !> A fixed-length, null-terminated string attribute (h5py reads it as str/bytes).
  subroutine attribute_text(writer, object, name, text)
    type(h5_writer_t), intent(inout) :: writer
    integer(hid_t), intent(in) :: object
    character(*), intent(in) :: name, text
    integer(hid_t) :: string_type, space, attribute
    integer(hsize_t) :: dims(1) = [1]
    integer :: status
    call h5tcopy_f(H5T_C_S1, string_type, status); call check(writer, status)
    call h5tset_size_f(string_type, int(max(len(text), 1), size_t), status); call check(writer, status)
    call h5tset_strpad_f(string_type, H5T_STR_NULLPAD_F, status); call check(writer, status)
    call h5screate_f(H5S_SCALAR_F, space, status); call check(writer, status)
    call h5acreate_f(object, name, string_type, space, attribute, status); call check(writer, status)
    call h5awrite_f(attribute, string_type, text, dims, status); call check(writer, status)
    call h5aclose_f(attribute, status); call check(writer, status)
    call h5sclose_f(space, status); call check(writer, status)
    call h5tclose_f(string_type, status); call check(writer, status)
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
    call h5screate_f(H5S_SCALAR_F, space, status); call check(writer, status)
    call h5acreate_f(object, name, H5T_NATIVE_DOUBLE, space, attribute, status); call check(writer, status)
    call h5awrite_f(attribute, H5T_NATIVE_DOUBLE, value, dims, status); call check(writer, status)
    call h5aclose_f(attribute, status); call check(writer, status)
    call h5sclose_f(space, status); call check(writer, status)
  end subroutine attribute_real
end module visco2d_hdf5
