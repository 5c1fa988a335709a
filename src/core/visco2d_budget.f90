!> Size before work: the memory (and, roughly, the time) a run will need,
!> estimated from the size of its mesh and its time axis before anything big
!> is allocated, and the memory limit a run must stay under.
!>
!> The memory model counts what the solvers allocate, in bytes (as real(dp),
!> so no product of counts can overflow), at the larger of two peaks. While
!> solving:
!>  - the banded stiffness (or effective stiffness, eq. [35]): n (b + 1)
!>    8 bytes for n equations of half-bandwidth b; with CHOLMOD (the default
!>    solver) its sparse factor, about 80 bytes per n log2(n) (fitted to level 4
!>    to 6 spheres; twice that in a run that refactors at a new Delta t), with
!>    the band solver a second band copy for the factor (the profile
!>    solver's envelope is at most that: counted as one), and a third in a
!>    run that assembles a new matrix while the
!>    factor of the previous one is still held (a new Delta t in a later TIME
!>    stage, or the relaxed moduli of a viscoelastic QUASISTATIC run);
!>  - per element: B at the Gauss points, the stresses, strains and trial
!>    states, and 128 bytes per Prony term with memory (the history of
!>    eq. [24]: 4 components at 4 Gauss points);
!>  - per equation: the solver's vectors and the field snapshots;
!>  - the history table (rows x columns x 8 bytes, as preallocated) and the
!>    kept contact columns S~^-1 e_c of the capacitance system;
!>  - a fixed base (program, libraries, the deck and its listing).
!> While writing (the solver's arrays are freed): the mesh, the history
!> table, every field snapshot (held in the record until results.h5 is
!> written) and the in-memory image of results.h5 (HDF5's core driver
!> allocates 1.125 times the file's expected size, at least 1 MiB, and the
!> image is copied out once more to be written: 2.125 times the file).
!> The per-item constants are fitted to the peak resident size (VmHWM) of
!> runs of every analysis kind; scripts/test_estimate.sh checks the estimate
!> against the measured peak of a spread of decks (within -10 % / +25 %).
!>
!> The limit is the smaller of the user's limit (`--max-memory SIZE`, or the
!> environment variable VISCO2D_MAX_MEMORY) and this machine's memory
!> (MemTotal in /proc/meminfo); without a user limit it is half of the
!> machine's memory, which leaves room for the system and one more job. A
!> process address-space limit (`ulimit -v`) lowers it too.
!>
!> A time limit is only the user's (`--max-time SECONDS`, or the environment
!> variable VISCO2D_MAX_TIME; none by default): a run whose rough time
!> estimate exceeds it is refused before it starts. Batch and fuzz runs use
!> it to bound what one deck may cost.
module visco2d_budget
  use, intrinsic :: iso_fortran_env, only: int64
  use visco2d_kinds, only: dp
  implicit none
  private

  public :: run_size_t, mesh_run_size, run_size
  public :: budget_static, budget_quasistatic, budget_dynamic
  public :: sphere_mesh_counts, grid_mesh_counts
  public :: memory_limit, set_memory_limit, machine_memory, address_space_limit, parse_memory_size
  public :: bytes_text, count_text, seconds_text, raise_hint
  public :: max_mesh_entities, long_run_seconds
  public :: time_limit, set_time_limit, read_limit_environment

  !> Analysis kinds as the cost model sees them.
  integer, parameter :: budget_static = 1, budget_quasistatic = 2, budget_dynamic = 3

  !> Most nodes or elements of a mesh: every count derived from them
  !> (2 equations per node, 4 sides and 12 node pairs per element) must fit a
  !> default integer.
  integer(int64), parameter :: max_mesh_entities = 100000000_int64

  !> A run estimated to take longer than this (s) is announced on stderr
  !> before it starts (the shipped decks take at most a few seconds).
  real(dp), parameter :: long_run_seconds = 20.0_dp

  ! Fitted constants of the memory model (bytes), at the peak of each analysis
  ! (STATIC: while the factor is held, before the snapshot is made).
  real(dp), parameter :: base_bytes = 22.0e6_dp           !< program, libraries (HDF5, CHOLMOD, BLAS), deck
  real(dp), parameter :: mesh_node_bytes = 64.0_dp        !< coordinates, numbers, lookup, renumbering
  real(dp), parameter :: mesh_element_bytes = 96.0_dp     !< connectivity, numbers, lines, material names
  real(dp), parameter :: static_element_bytes = 260.0_dp  !< strains and stresses at 4 Gauss points
  real(dp), parameter :: quasistatic_element_bytes = 300.0_dp !< stresses, trial stresses, moduli
  real(dp), parameter :: dynamic_element_bytes = 2200.0_dp !< B at 4 Gauss points (1 kB), 5 state arrays, kept maxima
  real(dp), parameter :: term_bytes = 128.0_dp            !< one Prony term's history at 4 Gauss points
  real(dp), parameter :: static_equation_bytes = 80.0_dp  !< load, displacement, reaction, scratch
  real(dp), parameter :: quasistatic_equation_bytes = 100.0_dp
  real(dp), parameter :: dynamic_equation_bytes = 240.0_dp !< the Wilson-theta vectors
  real(dp), parameter :: snapshot_node_bytes = 96.0_dp    !< u, v, a, 4 stresses, 2 invariants
  real(dp), parameter :: snapshot_element_bytes = 128.0_dp !< stresses at 4 Gauss points
  !> Kept contact columns per equation the plate may hold (their array grows
  !> by doubling; the plate holds fewer nodes than the lowest 2 % of the mesh).
  real(dp), parameter :: contact_column_factor = 0.75_dp
  !> CHOLMOD's factor and its copy of the matrix, per n log2(n) (n equations).
  real(dp), parameter :: sparse_factor_bytes = 80.0_dp
  !> results.h5 besides its arrays: groups, attributes (see h5_bytes in visco2d_output).
  real(dp), parameter :: h5_fixed_bytes = 65536.0_dp
  !> results.h5's mesh arrays: per node coordinates and ids, per element two
  !> connectivities, ids and materials.
  real(dp), parameter :: h5_node_bytes = 20.0_dp, h5_element_bytes = 40.0_dp
  !> results.h5's /xdmf/<snapshot>/ copies per node of each snapshot, what
  !> results.xmf shows (visco2d_xdmf): u, v, a with 3 components and the
  !> 9-component stress tensor, 18 doubles.
  real(dp), parameter :: h5_xdmf_node_bytes = 144.0_dp
  !> The core driver's buffer (1.125 times the expected file, at least 1 MiB)
  !> and the copy of the image written to disk (h5_open_file, write_image).
  real(dp), parameter :: h5_buffer_factor = 1.125_dp, h5_minimum_buffer = 1048576.0_dp

  ! Fitted constants of the time model (s), measured on one core of the
  ! development machine (AMD EPYC, OpenBLAS); see `run_size`.
  real(dp), parameter :: factor_seconds = 3.0e-11_dp      !< per n (b + 1)^2 (dpbtrf)
  real(dp), parameter :: solve_seconds = 1.2e-9_dp        !< per n (b + 1) per step (back-substitutions)
  real(dp), parameter :: equation_seconds = 2.0e-8_dp     !< per equation per step (vector updates)
  real(dp), parameter :: output_value_seconds = 5.0e-7_dp !< per history value written (text and HDF5)
  !> Bytes on disk per history value: ~14 characters in history.csv, 8 in results.h5.
  real(dp), parameter :: output_value_bytes = 22.0_dp
  real(dp), parameter :: static_element_seconds = 2.0e-6_dp  !< per element: assembly and stresses
  real(dp), parameter :: quasistatic_element_seconds = 3.0e-7_dp  !< per element per step
  real(dp), parameter :: dynamic_element_seconds = 1.5e-7_dp      !< per element per step
  real(dp), parameter :: quasistatic_term_seconds = 1.2e-7_dp     !< per Prony term per element per step
  real(dp), parameter :: dynamic_term_seconds = 3.5e-7_dp

  !> The size of a run, by part.
  type :: run_size_t
    integer(int64) :: nodes = 0, elements = 0, equations = 0
    integer(int64) :: half_bandwidth = 0   !< in equations, diagonal excluded
    integer(int64) :: steps = 0            !< time steps (0 for STATIC)
    integer(int64) :: history_rows = 0     !< rows of the history table
    integer :: band_copies = 2             !< band matrices held at the peak
    real(dp) :: band_bytes = 0.0_dp        !< all band copies
    real(dp) :: factor_bytes = 0.0_dp      !< CHOLMOD's sparse factor (0 with the band or profile solver)
    real(dp) :: element_bytes = 0.0_dp     !< per-element arrays, Prony history included
    real(dp) :: vector_bytes = 0.0_dp      !< per-equation arrays and snapshots
    real(dp) :: history_bytes = 0.0_dp     !< the history table
    real(dp) :: contact_bytes = 0.0_dp     !< kept contact columns
    real(dp) :: solve_bytes = 0.0_dp       !< the peak while solving: all of the above and the base
    integer :: written_snapshots = 0       !< field snapshots in results.h5
    real(dp) :: snapshot_bytes = 0.0_dp    !< all of them, held in the record until results.h5 is written
    real(dp) :: image_bytes = 0.0_dp       !< the in-memory results.h5 while it is written (buffer and copy)
    real(dp) :: write_bytes = 0.0_dp       !< the peak while writing: mesh, history, snapshots, image, base
    real(dp) :: total_bytes = 0.0_dp       !< the larger of solve_bytes and write_bytes
    real(dp) :: disk_bytes = 0.0_dp        !< the output files (history and snapshots)
    real(dp) :: seconds = 0.0_dp           !< rough CPU time on one core
  end type run_size_t

  ! The user's limit (bytes; 0: none given) and where it came from.
  integer(int64), save :: user_limit = 0
  character(len=64), save :: user_limit_origin = ''
  logical, save :: environment_read = .false.
  integer(int64), save :: machine_bytes = -1     ! MemTotal, read once (-1: not yet)
  ! The user's time limit (s; 0: none) and where it came from.
  real(dp), save :: user_seconds = 0.0_dp
  character(len=64), save :: user_seconds_origin = ''
  logical, save :: time_environment_read = .false.
  integer(int64), save :: address_space_bytes = -1  ! the soft RLIMIT_AS, read once (0: none)

  !> Address space the program needs besides what the model counts (its
  !> libraries, thread stacks and BLAS buffers: a small run does not start
  !> under `ulimit -v` 200 MB and does under 250 MB).
  real(dp), parameter :: address_space_reserve = 256.0_dp*1024.0_dp**2

contains

  !> Nodes and elements of MESH SPHERE LEVEL=level (see `sphere_grid`): with
  !> f = 2^(level-1), a core of f x 8f elements and 8f layers of 10f segments.
  pure subroutine sphere_mesh_counts(level, nodes, elements, half_bandwidth)
    integer, intent(in) :: level
    integer(int64), intent(out) :: nodes, elements, half_bandwidth
    integer(int64) :: f
    f = 2_int64**(max(1, min(level, 30)) - 1)
    nodes = (f + 1)*(8*f + 1) + 8*f*(10*f + 1)
    elements = 8*f*f + 80*f*f
    half_bandwidth = 32*f + 3                 ! a lower bound: level 1..5 have 35, 69, 133, 261, 517
  end subroutine sphere_mesh_counts

  !> Nodes and elements of a structured nr x nz grid (MESH RECT, MESH RING),
  !> and a lower bound of its half-bandwidth in any numbering: the bandwidth
  !> of the grid graph of (nr + 1) x (nz + 1) nodes is min(nr, nz) + 1, two
  !> equations per node.
  pure subroutine grid_mesh_counts(nr, nz, nodes, elements, half_bandwidth)
    integer, intent(in) :: nr, nz
    integer(int64), intent(out) :: nodes, elements, half_bandwidth
    nodes = (int(nr, int64) + 1)*(int(nz, int64) + 1)
    elements = int(nr, int64)*nz
    half_bandwidth = 2*(min(int(nr, int64), int(nz, int64)) + 1) + 1
  end subroutine grid_mesh_counts

  !> The least any analysis of a mesh of this size needs: the mesh, the
  !> stiffness and its factor (a STATIC run; with `sparse`, CHOLMOD's factor
  !> as run_size counts it). Used to refuse a mesh before it is generated.
  pure function mesh_run_size(nodes, elements, half_bandwidth, sparse) result(size)
    integer(int64), intent(in) :: nodes, elements, half_bandwidth
    logical, intent(in), optional :: sparse          !< CHOLMOD factors the matrix (default: a band factor)
    type(run_size_t) :: size
    size = run_size(budget_static, nodes, elements, half_bandwidth, steps=0_int64, stages=0, &
                    history_terms=0_int64, history_rows=1_int64, history_columns=0, snapshots=1, &
                    contact_equations=0_int64, sparse=sparse)
  end function mesh_run_size

  !> Memory and rough time of a run.
  !>
  !> The time model: a Cholesky factorization costs n (b + 1)^2 operations
  !> (one per stage, and per new Delta t); a step costs the back-substitutions,
  !> n (b + 1) each, vector updates (n) and a sweep over the elements and their
  !> Prony terms; writing the history costs per value. Fitted to runs of 200
  !> to 180,000 equations, it was within a factor 1.6 of their CPU time.
  !> STOP AT= may end a run before its last step, so the steps (and the time)
  !> are an upper bound.
  pure function run_size(analysis, nodes, elements, half_bandwidth, steps, stages, history_terms, &
                         history_rows, history_columns, snapshots, contact_equations, written_snapshots, sparse) &
                         result(size)
    integer, intent(in) :: analysis                  !< budget_static, budget_quasistatic or budget_dynamic
    integer(int64), intent(in) :: nodes, elements, half_bandwidth
    integer(int64), intent(in) :: steps              !< time steps (0 for STATIC)
    integer, intent(in) :: stages                    !< TIME stages
    integer(int64), intent(in) :: history_terms      !< Prony terms with memory, summed over the elements
    integer(int64), intent(in) :: history_rows       !< rows of the history table
    integer, intent(in) :: history_columns           !< its columns
    integer, intent(in) :: snapshots                 !< field snapshots held at the peak
    integer(int64), intent(in) :: contact_equations  !< equations the plate may hold (kept columns)
    integer, intent(in), optional :: written_snapshots !< field snapshots written to results.h5 (default: snapshots)
    logical, intent(in), optional :: sparse          !< CHOLMOD factors the matrix (default: a band or profile factor)
    type(run_size_t) :: size
    real(dp) :: n, b, elements_real, element_each, equation_each, factorizations, element_time, term_time
    real(dp) :: snapshot_each, h5_bytes
    logical :: sparse_factor

    size%nodes = nodes
    size%elements = elements
    size%equations = 2*nodes
    size%half_bandwidth = min(half_bandwidth, max(size%equations - 1, 0_int64))
    size%steps = steps
    size%history_rows = history_rows
    n = real(size%equations, dp)
    b = real(size%half_bandwidth, dp)
    elements_real = real(elements, dp)

    sparse_factor = .false.
    if (present(sparse)) sparse_factor = sparse
    size%written_snapshots = snapshots
    if (present(written_snapshots)) size%written_snapshots = written_snapshots
    size%band_copies = 2
    factorizations = 1.0_dp
    select case (analysis)
    case (budget_static)
      element_each = static_element_bytes
      equation_each = static_equation_bytes
      element_time = static_element_seconds
      term_time = 0.0_dp
    case (budget_quasistatic)
      element_each = quasistatic_element_bytes
      equation_each = quasistatic_equation_bytes
      element_time = quasistatic_element_seconds
      term_time = quasistatic_term_seconds
      if (history_terms > 0) then                     ! new relaxed moduli at every new Delta t
        size%band_copies = 3
        factorizations = real(stages + 1, dp)
      end if
    case default
      element_each = dynamic_element_bytes
      equation_each = dynamic_equation_bytes
      element_time = dynamic_element_seconds
      term_time = dynamic_term_seconds
      if (history_terms > 0) element_each = element_each + 128.0_dp   ! the history stress over dt
      if (stages > 1) size%band_copies = 3
      factorizations = real(max(stages, 1), dp)
    end select

    if (sparse_factor) then                           ! the band matrix and CHOLMOD's factor of it
      size%factor_bytes = sparse_factor_bytes*n*log(max(n, 2.0_dp))/log(2.0_dp)
      ! Refactored at a new Delta t: the peak grows by about one more factor (measured on
      ! viscoelastic QUASISTATIC blocks of 20,402 and 45,602 equations, 11 stages).
      if (size%band_copies == 3) size%factor_bytes = 2.0_dp*size%factor_bytes
      size%band_copies = 1
    end if
    size%band_bytes = size%band_copies*n*(b + 1.0_dp)*8.0_dp
    size%element_bytes = elements_real*(mesh_element_bytes + element_each + snapshots*snapshot_element_bytes) &
                         + real(history_terms, dp)*term_bytes
    size%vector_bytes = real(nodes, dp)*(mesh_node_bytes + snapshots*snapshot_node_bytes) + n*equation_each
    size%history_bytes = real(history_rows, dp)*history_columns*8.0_dp
    size%contact_bytes = n*contact_column_factor*real(contact_equations, dp)*8.0_dp
    size%solve_bytes = base_bytes + size%band_bytes + size%factor_bytes + size%element_bytes + size%vector_bytes &
                       + size%history_bytes + size%contact_bytes

    ! Writing: the record (mesh, history, every snapshot) and results.h5 in memory.
    snapshot_each = real(nodes, dp)*snapshot_node_bytes + elements_real*snapshot_element_bytes
    size%snapshot_bytes = size%written_snapshots*snapshot_each
    h5_bytes = h5_fixed_bytes + real(nodes, dp)*h5_node_bytes + elements_real*h5_element_bytes + size%history_bytes &
               + size%snapshot_bytes + size%written_snapshots*real(nodes, dp)*h5_xdmf_node_bytes
    size%image_bytes = max(h5_minimum_buffer, h5_buffer_factor*h5_bytes) + h5_bytes
    size%write_bytes = base_bytes + real(nodes, dp)*mesh_node_bytes + elements_real*mesh_element_bytes &
                       + size%history_bytes + size%snapshot_bytes + size%image_bytes
    size%total_bytes = max(size%solve_bytes, size%write_bytes)

    size%disk_bytes = real(history_rows, dp)*history_columns*output_value_bytes &
                      + max(size%written_snapshots, 1)*snapshot_each

    size%seconds = output_value_seconds*real(history_rows, dp)*history_columns &
                   + factorizations*factor_seconds*n*(b + 1.0_dp)**2 &
                   + real(max(steps, 1_int64), dp)*(solve_seconds*n*(b + 1.0_dp) + equation_seconds*n &
                       + element_time*elements_real + term_time*real(history_terms, dp))
  end function run_size

  !> This machine's memory in bytes (MemTotal of /proc/meminfo, read once), 0 if unknown.
  function machine_memory() result(bytes)
    integer(int64) :: bytes
    character(len=256) :: line
    integer :: unit, ios
    integer(int64) :: kilobytes
    if (machine_bytes >= 0) then
      bytes = machine_bytes
      return
    end if
    bytes = 0
    machine_bytes = 0
    open(newunit=unit, file='/proc/meminfo', status='old', action='read', iostat=ios)
    if (ios /= 0) return
    do
      read(unit, '(a)', iostat=ios) line
      if (ios /= 0) exit
      if (index(line, 'MemTotal:') == 1) then
        read(line(10:), *, iostat=ios) kilobytes
        if (ios == 0 .and. kilobytes > 0 .and. kilobytes < huge(kilobytes)/1024) bytes = kilobytes*1024_int64
        exit
      end if
    end do
    close(unit)
    machine_bytes = bytes
  end function machine_memory

  !> The soft limit of this process's address space (`ulimit -v`, "Max
  !> address space" in /proc/self/limits, read once) in bytes, 0 if none.
  function address_space_limit() result(bytes)
    integer(int64) :: bytes
    character(len=256) :: line
    character(len=32) :: soft
    integer :: unit, ios
    if (address_space_bytes >= 0) then
      bytes = address_space_bytes
      return
    end if
    bytes = 0
    open(newunit=unit, file='/proc/self/limits', status='old', action='read', iostat=ios)
    if (ios == 0) then
      do
        read(unit, '(a)', iostat=ios) line
        if (ios /= 0) exit
        if (index(line, 'Max address space') == 1) then
          read(line(len('Max address space') + 1:), *, iostat=ios) soft
          if (ios == 0 .and. verify(trim(soft), '0123456789') == 0 .and. len_trim(soft) <= 18) &
            read(soft, *, iostat=ios) bytes
          if (ios /= 0) bytes = 0
          exit
        end if
      end do
      close(unit)
    end if
    address_space_bytes = bytes
  end function address_space_limit

  !> A memory size: a number of bytes with an optional binary unit K, M, G
  !> or T (KiB ... TiB; "8G", "8GB", "8GiB", "512m", "1.5G"). ok is false for
  !> anything else, for 0 and for more than 2^62 bytes.
  pure subroutine parse_memory_size(text, bytes, ok)
    character(*), intent(in) :: text
    integer(int64), intent(out) :: bytes
    logical, intent(out) :: ok
    character(:), allocatable :: number, unit
    real(dp) :: value, scale
    integer :: split, ios, i
    bytes = 0
    ok = .false.
    number = trim(adjustl(text))
    split = scan(number, 'KkMmGgTtBbIi')          ! the unit: the letters after the number
    if (split == 0) then
      unit = ''
    else
      unit = number(split:)
      number = number(1:split - 1)
    end if
    if (len(number) == 0 .or. verify(number, '0123456789.') /= 0) return
    if (count([(number(i:i) == '.', i = 1, len(number))]) > 1) return
    if (scan(number, '0123456789') == 0) return
    read(number, *, iostat=ios) value
    if (ios /= 0) return
    select case (unit)
    case ('', 'B', 'b')
      scale = 1.0_dp
    case ('K', 'k', 'KB', 'kB', 'kb', 'KiB', 'kiB')
      scale = 1024.0_dp
    case ('M', 'm', 'MB', 'mb', 'MiB')
      scale = 1024.0_dp**2
    case ('G', 'g', 'GB', 'gb', 'GiB')
      scale = 1024.0_dp**3
    case ('T', 't', 'TB', 'tb', 'TiB')
      scale = 1024.0_dp**4
    case default
      return
    end select
    if (value*scale < 1.0_dp .or. value*scale > 2.0_dp**62) return
    bytes = int(value*scale, int64)
    ok = .true.
  end subroutine parse_memory_size

  !> Set the user's memory limit from the text of `--max-memory`; message is
  !> '' if the text is a size, else why not.
  subroutine set_memory_limit(text, origin, message)
    character(*), intent(in) :: text, origin
    character(:), allocatable, intent(out) :: message
    integer(int64) :: bytes
    logical :: ok
    call parse_memory_size(text, bytes, ok)
    message = ''
    if (.not. ok) then
      message = origin//' "'//text//'" is not a memory size (expected e.g. 8G, 512M, 1.5G or a '// &
                'number of bytes; K, M, G, T are powers of 1024)'
      return
    end if
    user_limit = bytes
    user_limit_origin = origin
    environment_read = .true.          ! the option overrides the environment
  end subroutine set_memory_limit

  !> The memory limit of a run (bytes), what set it (text for messages) and
  !> whether the user can raise it (false when it is the machine's memory).
  !> Reads VISCO2D_MAX_MEMORY the first time unless --max-memory was given or
  !> the command line read it (read_limit_environment, which refuses a value
  !> that is not a size); here, for a caller other than the command line,
  !> such a value is reported on stderr and ignored.
  subroutine memory_limit(limit, origin, raisable)
    real(dp), intent(out) :: limit
    character(:), allocatable, intent(out) :: origin
    logical, intent(out) :: raisable
    character(:), allocatable :: text, message
    real(dp) :: machine
    if (.not. environment_read) then
      environment_read = .true.
      text = environment_value('VISCO2D_MAX_MEMORY')
      if (len(text) > 0) then
        call set_memory_limit(text, 'VISCO2D_MAX_MEMORY', message)
        if (len(message) > 0) write(0, '(a)') 'visco2d: warning: '//message//'; using the default limit'
      end if
    end if
    machine = real(machine_memory(), dp)
    raisable = .true.
    if (user_limit > 0) then
      limit = real(user_limit, dp)
      origin = 'the limit of '//bytes_text(limit)//' set by '//trim(user_limit_origin)
      if (machine > 0.0_dp .and. machine < limit) then
        limit = machine
        origin = "this machine's memory ("//bytes_text(machine)//', MemTotal in /proc/meminfo)'
        raisable = .false.
      end if
    else if (machine > 0.0_dp) then
      limit = 0.5_dp*machine
      origin = 'the default limit of '//bytes_text(limit)//", half of this machine's "//bytes_text(machine)
    else
      limit = 4.0_dp*1024.0_dp**3
      origin = 'the default limit of '//bytes_text(limit)//" (this machine's memory is unknown)"
    end if
    if (address_space_limit() > 0) then
      if (real(address_space_limit(), dp) - address_space_reserve < limit) then
        limit = max(real(address_space_limit(), dp) - address_space_reserve, 0.0_dp)
        origin = "this process's address-space limit (ulimit -v, "//bytes_text(real(address_space_limit(), dp))// &
                 ', less '//bytes_text(address_space_reserve)//' for the program)'
        raisable = .false.
      end if
    end if
  end subroutine memory_limit

  !> Bytes in binary units with 3 significant digits: "512 B", "1.50 KiB", "23.4 GiB".
  pure function bytes_text(bytes) result(text)
    real(dp), intent(in) :: bytes
    character(:), allocatable :: text
    character(len=*), parameter :: units(0:6) = ['B  ', 'KiB', 'MiB', 'GiB', 'TiB', 'PiB', 'EiB']
    character(len=32) :: buffer
    real(dp) :: value
    integer :: k
    value = max(bytes, 0.0_dp)
    k = 0
    do while (value >= 1024.0_dp .and. k < 6)
      value = value/1024.0_dp
      k = k + 1
    end do
    if (k == 0) then
      write(buffer, '(i0)') nint(value)
    else if (value >= 100.0_dp) then
      write(buffer, '(i0)') nint(value)
    else if (value >= 10.0_dp) then
      write(buffer, '(f0.1)') value
    else
      write(buffer, '(f0.2)') value
    end if
    text = trim(buffer)//' '//trim(units(k))
    if (bytes >= 1024.0_dp**7) text = '> 1024 EiB'
  end function bytes_text

  !> A count with thousands separators: 18,006,002.
  pure function count_text(value) result(text)
    integer(int64), intent(in) :: value
    character(:), allocatable :: text
    character(len=24) :: buffer
    character(:), allocatable :: digits
    integer :: i, n
    write(buffer, '(i0)') abs(value)
    digits = trim(buffer)
    n = len(digits)
    text = ''
    do i = 1, n
      text = text//digits(i:i)
      if (i < n .and. mod(n - i, 3) == 0) text = text//','
    end do
    if (value < 0) text = '-'//text
  end function count_text

  !> A duration for people: "0.4 s", "35 s", "12 min", "3.5 h", "2.1 days".
  pure function seconds_text(seconds) result(text)
    real(dp), intent(in) :: seconds
    character(:), allocatable :: text
    character(len=32) :: buffer
    if (seconds < 10.0_dp) then
      write(buffer, '(f3.1, a)') max(seconds, 0.1_dp), ' s'
    else if (seconds < 120.0_dp) then
      write(buffer, '(i0, a)') nint(seconds), ' s'
    else if (seconds < 7200.0_dp) then
      write(buffer, '(i0, a)') nint(seconds/60.0_dp), ' min'
    else if (seconds < 172800.0_dp) then
      write(buffer, '(f0.1, a)') seconds/3600.0_dp, ' h'
    else if (seconds < 3.0e9_dp) then
      write(buffer, '(f0.1, a)') seconds/86400.0_dp, ' days'
    else
      buffer = 'more than 100 years'
    end if
    text = trim(buffer)
  end function seconds_text
  !> Set the user's time limit from the text of `--max-time` (seconds > 0);
  !> message is '' if the text is such a number, else why not.
  subroutine set_time_limit(text, origin, message)
    character(*), intent(in) :: text, origin
    character(:), allocatable, intent(out) :: message
    real(dp) :: seconds
    integer :: ios
    message = ''
    seconds = -1.0_dp
    if (verify(trim(adjustl(text)), '0123456789.eE+-') == 0 .and. len_trim(text) > 0) &
      read(text, *, iostat=ios) seconds
    if (.not. (seconds > 0.0_dp .and. seconds < 1.0e12_dp)) then
      message = origin//' "'//text//'" is not a number of seconds > 0'
      return
    end if
    user_seconds = seconds
    user_seconds_origin = origin
    time_environment_read = .true.     ! the option overrides the environment
  end subroutine set_time_limit

  !> The user's time limit (s; 0: none) and what set it. Reads
  !> VISCO2D_MAX_TIME the first time unless --max-time was given or the
  !> command line read it (read_limit_environment, which refuses a value that
  !> is not a number of seconds); here such a value is reported and ignored.
  subroutine time_limit(seconds, origin)
    real(dp), intent(out) :: seconds
    character(:), allocatable, intent(out) :: origin
    character(:), allocatable :: text, message
    if (.not. time_environment_read) then
      time_environment_read = .true.
      text = environment_value('VISCO2D_MAX_TIME')
      if (len(text) > 0) then
        call set_time_limit(text, 'VISCO2D_MAX_TIME', message)
        if (len(message) > 0) write(0, '(a)') 'visco2d: warning: '//message//'; no time limit'
      end if
    end if
    seconds = user_seconds
    origin = trim(user_seconds_origin)
  end subroutine time_limit

  !> Read VISCO2D_MAX_MEMORY and VISCO2D_MAX_TIME (each unless its option,
  !> --max-memory or --max-time, was given): message is '' if both are unset,
  !> empty or valid, else why the first invalid one is refused. The command
  !> line calls it once its options are read and refuses a bad value as it
  !> refuses a bad option (exit 2): ignored with a warning, a value such as
  !> "1s" or "0" left the run without the limit it asked for.
  subroutine read_limit_environment(message)
    character(:), allocatable, intent(out) :: message
    character(:), allocatable :: text
    message = ''
    if (.not. environment_read) then
      environment_read = .true.
      text = environment_value('VISCO2D_MAX_MEMORY')
      if (len(text) > 0) call set_memory_limit(text, 'VISCO2D_MAX_MEMORY', message)
      if (len(message) > 0) return
    end if
    if (.not. time_environment_read) then
      time_environment_read = .true.
      text = environment_value('VISCO2D_MAX_TIME')
      if (len(text) > 0) call set_time_limit(text, 'VISCO2D_MAX_TIME', message)
    end if
  end subroutine read_limit_environment

  !> The value of an environment variable ('' when it is not set or empty).
  function environment_value(name) result(text)
    character(*), intent(in) :: name
    character(:), allocatable :: text
    integer :: n, status
    text = ''
    call get_environment_variable(name, length=n, status=status)
    if (status /= 0 .or. n <= 0) return
    deallocate(text)
    allocate(character(len=n) :: text)
    call get_environment_variable(name, text)
  end function environment_value

  !> How to lift a memory limit, for messages.
  pure function raise_hint(raisable) result(hint)
    logical, intent(in) :: raisable
    character(:), allocatable :: hint
    if (raisable) then
      hint = ' (a coarser mesh, or raise the limit with --max-memory SIZE or VISCO2D_MAX_MEMORY=SIZE)'
    else
      hint = ' (a coarser mesh)'
    end if
  end function raise_hint
end module visco2d_budget
