!> Restart files (&run checkpoint, spallbar DECK --restart FILE, doc/outputs.md).
!>
!> A checkpoint holds everything a run needs to go on as if it had never stopped: every
!> component of state_t (float64 written and read back bit for bit), the summary the run
!> carries from step to step (the energy guard's reference and scale among it) and the
!> marks of its outputs (bytes of each text file, rows of each PREFIX.h5 table). With it,
!> what identifies the run, checked on restart: the program (version and source digest,
!> doc/build.md), the deck (every echoed
!> value except title, t_end, checkpoint, checkpoint_every and profile times after the
!> checkpoint), the mesh's dt and cells, a load table's values. Layout in doc/outputs.md.
!> The file is written as FILE.part and renamed: a run killed while writing it keeps the
!> previous checkpoint. Read back, every value a restart uses is under the checksum (format
!> 3) and every count, index and list is range-checked before use (doc/outputs.md).
module spb_checkpoint
   use, intrinsic :: iso_fortran_env, only: int64
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan
   use spb_kinds, only: wp
   use spb_identity, only: program_identity, build_revision
   use spb_error, only: spb_error_t, make_error, exit_input, exit_runtime
   use spb_strings, only: itoa, rtoa
   use spb_deck, only: deck_record_t
   use spb_mesh, only: mesh_t
   use spb_load, only: load_t, load_table
   use spb_state, only: state_t, damage_t
   use spb_ends, only: face_top, face_bottom, define_ends, is_striker, striker_fields, &
      has_base
   use spb_field_io, only: field_io_t
   use spb_summary, only: run_summary_t, summary_fields, summary_problem
   use spb_diagnostics, only: diag_problem
   use spb_output, only: output_marks_t, h5_deck_header, text_extensions, tail_len, text_count
   use spb_hdf5, only: h5file_t, h5_create, h5_open_read, h5_close, h5_group, h5_attr, &
      h5_write, h5_get, h5_get_attr, h5_has_attr
   use spb_sys, only: sys_rename
   implicit none
   private
   public :: checkpoint_t, write_checkpoint, read_checkpoint, check_checkpoint_path

   !> Formats (doc/outputs.md): 3 sums every value a restart reads; 2 (0.2.0 before it)
   !> summed the state, summary and output counts only; 1 had no checksum (refused).
   character(len=*), parameter :: format_name = 'spallbar checkpoint 3'
   character(len=*), parameter :: format_2 = 'spallbar checkpoint 2'
   character(len=*), parameter :: format_1 = 'spallbar checkpoint 1'
   character(len=1), parameter :: nl = achar(10)

   !> One entry of a field list (state_fields): written or read back.
   interface field
      module procedure field_int, field_real, field_logical
   end interface field
   interface array_field
      module procedure array_reals, array_ints, array_logicals
   end interface array_field

   !> A checksum: two Fletcher sums modulo the prime 4294967291 over the 16-bit pieces of
   !> each value counted (an integer as int64, a real's bits, a string's length then each
   !> character), in the order they are counted. Any one changed bit changes both.
   type :: fletcher_t
      integer(int64) :: sum1 = 1_int64         !! first Fletcher sum
      integer(int64) :: sum2 = 0_int64         !! second Fletcher sum
   end type fletcher_t

   !> A checkpoint file being written or read, and its checksum in two parts: fields, every
   !> value the field lists carry (state, run summary, output counts: all format 2 summed);
   !> rest, everything else a restart reads (the identity, profile times, a load table, the
   !> text files' marks), in the order write_checkpoint writes them. As a field_io_t it
   !> writes or reads the field lists of other modules (spb_summary summary_fields).
   type, extends(field_io_t) :: ck_file_t
      type(h5file_t) :: h5                     !! the HDF5 file
      type(fletcher_t) :: fields               !! the field lists' values
      type(fletcher_t) :: rest                 !! the other values a restart reads
   contains
      procedure :: int_field => io_int
      procedure :: real_field => io_real
      procedure :: has => io_has
      procedure :: later_reals => io_later_reals
   end type ck_file_t

   integer(int64), parameter :: fletcher_prime = 4294967291_int64

   !> What a restart continues from.
   type :: checkpoint_t
      type(state_t) :: st
      type(run_summary_t) :: summary
      type(output_marks_t) :: marks
      character(len=:), allocatable :: program   !! who wrote it (/identity program)
   end type checkpoint_t

   !> Deck variables added after checkpoints existed ('group:name'): not given, they keep the
   !> behaviour of before, and a checkpoint that predates them fits a deck that leaves them out.
   character(len=*), parameter :: later_variables(6) = [character(len=24) :: 'segments:area', &
      'segments:fracture_energy', 'ends:base_gap_top', 'gauges:side', &
      'segments:damage_integral', 'segments:damage_exponent']

contains

   !> Refuse (exit 2) a checkpoint path that cannot be written, before the run starts.
   subroutine check_checkpoint_path(path, err)
      character(len=*), intent(in) :: path   !! checkpoint file
      type(spb_error_t), allocatable, intent(out) :: err   !! the error (allocated: it failed)
      integer :: u, ios
      character(len=256) :: msg
      open(newunit=u, file=path // '.part', status='replace', action='write', iostat=ios, &
           iomsg=msg)
      if (ios /= 0) then
         call make_error(err, '&run: checkpoint = ''' // path // ''': cannot write ''' // &
                         path // '.part'': ' // trim(msg))
         return
      end if
      close(u, status='delete')
   end subroutine check_checkpoint_path

   !> Write the checkpoint of a run at its state's step.
   subroutine write_checkpoint(path, rec, mesh, load, st, summary, marks, err)
      character(len=*), intent(in) :: path   !! checkpoint file
      type(deck_record_t), intent(in) :: rec   !! the deck's record
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(load_t), intent(in) :: load     !! the end load
      type(state_t), intent(inout) :: st       !! only read (state_fields also reads back)
      type(run_summary_t), intent(in) :: summary   !! the run's summary
      type(output_marks_t), intent(in) :: marks   !! how far the outputs reach
      type(spb_error_t), allocatable, intent(out) :: err   !! the error (allocated: it failed)
      type(ck_file_t) :: cf
      type(run_summary_t) :: run_copy
      type(output_marks_t) :: marks_copy
      logical :: ok
      integer :: k
      call h5_create(cf%h5, path // '.part')
      call h5_deck_header(cf%h5, rec)
      call h5_attr(cf%h5, '/', 'format', format_name)
      call h5_attr(cf%h5, '/', 'step', st%step)
      call h5_attr(cf%h5, '/', 't', real(st%step, wp) * mesh%dt)
      ! what identifies the run
      ! what identifies the run, each value counted in the rest of the checksum in the
      ! order read_checkpoint reads it
      call h5_group(cf%h5, '/identity')
      call h5_attr(cf%h5, '/identity', 'program', program_identity())
      call mix_text(cf%rest, trim(program_identity()))
      call h5_attr(cf%h5, '/identity', 'revision', build_revision())
      call mix_text(cf%rest, trim(build_revision()))
      call h5_attr(cf%h5, '/identity', 'deck', deck_identity(rec))
      call mix_text(cf%rest, trim(deck_identity(rec)))
      call h5_attr(cf%h5, '/identity', 'dt', mesh%dt)
      call mix(cf%rest, transfer(mesh%dt, 0_int64))
      call h5_attr(cf%h5, '/identity', 'cells', mesh%n)
      call mix(cf%rest, int(mesh%n, int64))
      if (load%kind == load_table) then
         call h5_write(cf%h5, '/identity/load_t', load%t, 's')
         call mix_reals(cf%rest, load%t)
         call h5_write(cf%h5, '/identity/load_p', load%p, 'Pa')
         call mix_reals(cf%rest, load%p)
      end if
      call h5_attr(cf%h5, '/identity', 'n_profiles', size(rec%profile_times))
      call mix(cf%rest, int(size(rec%profile_times), int64))
      if (size(rec%profile_times) > 0) then
         call h5_write(cf%h5, '/identity/profile_times', rec%profile_times, 's')
         call mix_reals(cf%rest, rec%profile_times)
      end if
      call h5_group(cf%h5, '/state')
      call state_fields(cf, st, .true.)
      ! the run's summary
      call h5_group(cf%h5, '/run')
      run_copy = summary
      cf%writing = .true.
      call summary_fields(run_copy, cf, '/run')
      ! how far the outputs reach (byte counts as float64: exact below 2^53)
      call h5_group(cf%h5, '/outputs')
      do k = 1, text_count(rec)
         call h5_attr(cf%h5, '/outputs', 'body' // text_extensions(k), real(marks%body(k), wp))
         call mix(cf%rest, transfer(real(marks%body(k), wp), 0_int64))
         call h5_attr(cf%h5, '/outputs', 'tail_bytes' // text_extensions(k), marks%tail_n(k))
         call mix(cf%rest, int(marks%tail_n(k), int64))
         call h5_attr(cf%h5, '/outputs', 'tail' // text_extensions(k), &
                      marks%tail(k)(1:max(0, marks%tail_n(k))))
         ! read back without its trailing blanks: counted so
         call mix_text(cf%rest, trim(marks%tail(k)(1:max(0, marks%tail_n(k)))))
      end do
      marks_copy = marks
      call count_fields(cf, marks_copy, .true., size(rec%gauge_x) > 0)
      call h5_attr(cf%h5, '/', 'checksum', checksum_text(cf, 3))
      call h5_close(cf%h5)
      if (allocated(cf%h5%error)) then
         call make_error(err, '&run: checkpoint: ' // cf%h5%error, code=exit_runtime)
         return
      end if
      call sys_rename(path // '.part', path, ok)
      if (.not. ok) call make_error(err, '&run: checkpoint: cannot rename ''' // path // &
                                    '.part'' to ''' // path // '''', code=exit_runtime)
   end subroutine write_checkpoint

   !> The one list of what the checkpoint keeps of state_t, written (writing) or read back:
   !> arrays as datasets under /state with their lower bound and size as attributes of
   !> /state, scalars as attributes, logicals as 0/1 (float64 bit for bit).
   subroutine state_fields(ck, st, writing)
      type(ck_file_t), intent(inout) :: ck   !! the checkpoint file and its checksum
      type(state_t), intent(inout) :: st   !! the state
      logical, intent(in) :: writing       !! write (else read back)
      logical :: offsets
      real(wp) :: retry(2)
      call field(ck, writing, '/state', 'n', st%step)   ! names as in 0.1 checkpoints
      call field(ck, writing, '/state', 'n_breakable', st%n_breakable)
      call field(ck, writing, '/state', 'n_split', st%n_split)
      call field(ck, writing, '/state', 'n_frag_ids', st%gen%n_frag_ids)
      call field(ck, writing, '/state', 'n_cut', st%fm%n_cut)
      call field(ck, writing, '/state', 'n_skip', st%n_skip)
      call field(ck, writing, '/state', 's_scale', st%s_scale)
      call field(ck, writing, '/state', 'strain_cut', st%fm%strain_cut)
      call field(ck, writing, '/state', 'e_contact', st%ledger%e_contact)
      call field(ck, writing, '/state', 's_static_top', st%ends(face_top)%s_static)
      call field(ck, writing, '/state', 's_static_bot', st%ends(face_bottom)%s_static)
      call field(ck, writing, '/state', 'v_far_top', st%ends(face_top)%v_far)
      call field(ck, writing, '/state', 'v_far_bot', st%ends(face_bottom)%v_far)
      call field(ck, writing, '/state', 'w_in_top', st%ends(face_top)%w_in)
      call field(ck, writing, '/state', 'w_in_bot', st%ends(face_bottom)%w_in)
      call field(ck, writing, '/state', 'w_load', st%ledger%w_load)
      call field(ck, writing, '/state', 'w_transmit', st%ledger%w_transmit)
      call field(ck, writing, '/state', 'e_fracture', st%ledger%e_fracture)
      call field(ck, writing, '/state', 'e_join', st%ledger%e_join)
      call field(ck, writing, '/state', 'e_shift', st%ledger%e_shift)
      call field(ck, writing, '/state', 'p_shift', st%ledger%p_shift)
      call field(ck, writing, '/state', 'w_wave', st%ledger%w_wave)
      call field(ck, writing, '/state', 'e_lost_wave', st%ledger%e_lost_wave)
      call field(ck, writing, '/state', 'i_ends', st%ledger%i_ends)
      call field(ck, writing, '/state', 'i_support', st%ledger%i_support)
      call field(ck, writing, '/state', 'u_base', st%ends(face_bottom)%u_contact)
      call field(ck, writing, '/state', 'v_land_top', st%ends(face_top)%v_land)
      call field(ck, writing, '/state', 'v_land_bot', st%ends(face_bottom)%v_land)
      call field(ck, writing, '/state', 'base_contact', st%ends(face_bottom)%contact)
      call field(ck, writing, '/state', 'landing_top', st%ends(face_top)%landing)
      call field(ck, writing, '/state', 'landing_bot', st%ends(face_bottom)%landing)
      ! added later (a checkpoint without it was written by a version without the credit)
      call later_field(ck, writing, '/state', 'u_credit', st%u_credit)
      ! added with the constant-velocity ends (0 in a checkpoint of a version without them)
      call later_field(ck, writing, '/state', 'v_end_top', st%ends(face_top)%v_end)
      call later_field(ck, writing, '/state', 'v_end_bot', st%ends(face_bottom)%v_end)
      call later_field(ck, writing, '/state', 'w_support', st%ledger%w_support)
      ! added with x_drift (0 in a checkpoint of a version without it)
      call later_field(ck, writing, '/state', 'm_drift', st%ledger%m_drift)
      ! added with the rings' retries (0 in a checkpoint of a version without them): steps,
      ! as reals (exact below 2^53)
      retry = real([st%ring_next, st%ring_wait], wp)
      call later_field(ck, writing, '/state', 'ring_next', retry(1))
      call later_field(ck, writing, '/state', 'ring_wait', retry(2))
      ! (a value that is no step count is kept as -1: state_problem refuses it)
      st%ring_next = -1
      st%ring_wait = -1
      if (retry(1) >= 0.0_wp .and. retry(1) <= real(huge(1), wp)) st%ring_next = nint(retry(1))
      if (retry(2) >= 0.0_wp .and. retry(2) <= real(huge(1), wp)) st%ring_wait = nint(retry(2))
      ! a striking mass (only a run that has one)
      if (any(is_striker(st%ends))) then
         ck%writing = writing
         call field(ck, writing, '/state', 'e_impactor', st%ledger%e_impactor)
         if (is_striker(st%ends(face_top))) call striker_fields(st%ends(face_top), face_top, ck)
         if (is_striker(st%ends(face_bottom))) call striker_fields(st%ends(face_bottom), &
                                                                face_bottom, ck)
      end if
      ! a base above the bar (only a run that has one)
      if (has_base(st%ends(face_top))) then
         call field(ck, writing, '/state', 'u_base_top', st%ends(face_top)%u_contact)
         call field(ck, writing, '/state', 'base_contact_top', st%ends(face_top)%contact)
      end if
      call cohesive_fields(ck, st, writing, offsets)
      ! time-dependent fracture (spb_state damage_t; only a run that has it, so a checkpoint
      ! of a run without it is what it was before it existed)
      if (.not. writing) st%dmg%on = h5_has_attr(ck%h5, '/state', 'dmg_d:size')
      if (st%dmg%on) then
         call array_field(ck, writing, 'dmg_k', st%dmg%k)
         call array_field(ck, writing, 'dmg_lambda', st%dmg%lambda)
         call array_field(ck, writing, 'dmg_d', st%dmg%d)
      end if
      call array_field(ck, writing, 'ua', st%ua)
      call array_field(ck, writing, 'ub', st%ub)
      call array_field(ck, writing, 'dua', st%dua)
      call array_field(ck, writing, 'dub', st%dub)
      call array_field(ck, writing, 's', st%s)
      call array_field(ck, writing, 's_old', st%s_old)
      call array_field(ck, writing, 'sec', st%section)
      call array_field(ck, writing, 'strength', st%strength)
      call array_field(ck, writing, 'cell_strength', st%cell_strength)
      call array_field(ck, writing, 'split', st%split)
      call array_field(ck, writing, 'frag_id', st%gen%frag_id)
      call array_field(ck, writing, 'frag_parent', st%gen%frag_parent)
      call array_field(ck, writing, 'frag_birth', st%gen%frag_birth)
      call array_field(ck, writing, 'cut', st%fm%cut)
      call array_field(ck, writing, 'skip_test', st%skip_test)
      call array_field(ck, writing, 'joined', st%joined)
      call array_field(ck, writing, 'is_cut', st%fm%is_cut)
      call array_field(ck, writing, 'cracked', st%cracked)
      if (offsets) call openings_of_offsets(st)
   end subroutine state_fields

   !> A checkpoint written before the cracks kept their own opening holds, in its place, what
   !> rigid shifts added to the faces' distance (coh_offset): the opening is that distance
   !> less it, ub - ua - offset, to the positions' round-off (doc/method.md, "Cohesive
   !> cracks").
   pure subroutine openings_of_offsets(st)
      type(state_t), intent(inout) :: st   !! the state read back, offsets in coh%opening
      integer :: i
      if (.not. (allocated(st%coh%opening) .and. allocated(st%coh%active) .and. &
                 allocated(st%ua) .and. allocated(st%ub))) return
      if (.not. (bounds_are(st%ua, lbound(st%coh%opening, 1), ubound(st%coh%opening, 1)) .and. &
                 bounds_are(st%ub, lbound(st%coh%opening, 1), ubound(st%coh%opening, 1)) .and. &
                 bounds_are(st%coh%opening, lbound(st%coh%active, 1), &
                            ubound(st%coh%active, 1)))) return
      do i = lbound(st%coh%opening, 1), ubound(st%coh%opening, 1)
         st%coh%opening(i) = merge(st%ub(i) - st%ua(i) - st%coh%opening(i), 0.0_wp, &
                                   st%coh%active(i))
      end do
   end subroutine openings_of_offsets

   !> The cohesive cracks' part of the state (spb_state cohesive_t): only in a run that has
   !> them, so a checkpoint of a run without them is what it was before they existed; read
   !> back where the checkpoint has them. One written before the cracks kept their opening
   !> holds coh_offset in its place (offsets: read into coh%opening, for
   !> openings_of_offsets once the positions are read).
   subroutine cohesive_fields(ck, st, writing, offsets)
      type(ck_file_t), intent(inout) :: ck   !! the checkpoint file and its checksum
      type(state_t), intent(inout) :: st   !! the state
      logical, intent(in) :: writing       !! write (else read back)
      logical, intent(out) :: offsets      !! coh%opening holds a checkpoint's coh_offset
      offsets = .false.
      if (.not. writing) st%coh%on = h5_has_attr(ck%h5, '/state', 'coh_n_active')
      if (.not. st%coh%on) return
      call field(ck, writing, '/state', 'coh_n_active', st%coh%n_active)
      call field(ck, writing, '/state', 'w_cohesive', st%ledger%w_cohesive)
      call field(ck, writing, '/state', 'e_closing', st%ledger%e_closing)
      call field(ck, writing, '/state', 'e_traction', st%ledger%e_traction)
      call array_field(ck, writing, 'coh_gc', st%coh%gc)
      call array_field(ck, writing, 'coh_r', st%coh%r)
      call array_field(ck, writing, 'coh_dc', st%coh%dc)
      call array_field(ck, writing, 'coh_dmax', st%coh%dmax)
      call array_field(ck, writing, 'coh_q', st%coh%q)
      offsets = .not. writing .and. .not. h5_has_attr(ck%h5, '/state', 'coh_opening:size')
      if (offsets) then
         call array_field(ck, writing, 'coh_offset', st%coh%opening)
      else
         call array_field(ck, writing, 'coh_opening', st%coh%opening)
      end if
      call array_field(ck, writing, 'coh_active', st%coh%active)
   end subroutine cohesive_fields

   !> A real attribute of group added after checkpoints existed: always written; read back
   !> (and counted in the checksum) only where the checkpoint has it, so that one written
   !> before it still matches its checksum.
   subroutine later_field(ck, writing, group, name, v)
      type(ck_file_t), intent(inout) :: ck   !! the checkpoint file and its checksum
      logical, intent(in) :: writing       !! write (else read back)
      character(len=*), intent(in) :: group   !! group path
      character(len=*), intent(in) :: name   !! field name
      real(wp), intent(inout) :: v         !! the value
      if (writing .or. h5_has_attr(ck%h5, group, name)) call field_real(ck, writing, group, &
                                                                       name, v)
   end subroutine later_field

   !> A scalar field: an attribute of group, written or read back.
   subroutine field_int(ck, writing, group, name, v)
      type(ck_file_t), intent(inout) :: ck   !! the checkpoint file and its checksum
      logical, intent(in) :: writing       !! write (else read back)
      character(len=*), intent(in) :: group   !! group path
      character(len=*), intent(in) :: name   !! field name
      integer, intent(inout) :: v          !! the value
      if (writing) then
         call h5_attr(ck%h5, group, name, v)
      else
         call h5_get_attr(ck%h5, group, name, v)
      end if
      call mix(ck%fields, int(v, int64))
   end subroutine field_int

   !> A real scalar field: an attribute of group, written or read back.
   subroutine field_real(ck, writing, group, name, v)
      type(ck_file_t), intent(inout) :: ck   !! the checkpoint file and its checksum
      logical, intent(in) :: writing       !! write (else read back)
      character(len=*), intent(in) :: group   !! group path
      character(len=*), intent(in) :: name   !! field name
      real(wp), intent(inout) :: v         !! the value
      if (writing) then
         call h5_attr(ck%h5, group, name, v)
      else
         call h5_get_attr(ck%h5, group, name, v)
      end if
      call mix(ck%fields, transfer(v, 0_int64))
   end subroutine field_real

   !> A logical as the integer 0 or 1.
   subroutine field_logical(ck, writing, group, name, v)
      type(ck_file_t), intent(inout) :: ck   !! the checkpoint file and its checksum
      logical, intent(in) :: writing       !! write (else read back)
      character(len=*), intent(in) :: group   !! group path
      character(len=*), intent(in) :: name   !! field name
      logical, intent(inout) :: v          !! the value
      integer :: flag
      flag = merge(1, 0, v)
      call field_int(ck, writing, group, name, flag)
      if (.not. writing) v = flag /= 0
   end subroutine field_logical

   !> field_io_t's integer field: field_int in the direction io%writing.
   subroutine io_int(io, group, name, v)
      class(ck_file_t), intent(inout) :: io   !! the checkpoint file and its checksum
      character(len=*), intent(in) :: group   !! group path
      character(len=*), intent(in) :: name   !! field name
      integer, intent(inout) :: v          !! the value
      call field_int(io, io%writing, group, name, v)
   end subroutine io_int

   !> field_io_t's real field: field_real in the direction io%writing.
   subroutine io_real(io, group, name, v)
      class(ck_file_t), intent(inout) :: io   !! the checkpoint file and its checksum
      character(len=*), intent(in) :: group   !! group path
      character(len=*), intent(in) :: name   !! field name
      real(wp), intent(inout) :: v         !! the value
      call field_real(io, io%writing, group, name, v)
   end subroutine io_real

   !> field_io_t's question: the checkpoint has the attribute name of group.
   logical function io_has(io, group, name)
      class(ck_file_t), intent(inout) :: io   !! the checkpoint file and its checksum
      character(len=*), intent(in) :: group   !! group path
      character(len=*), intent(in) :: name   !! field name
      io_has = h5_has_attr(io%h5, group, name)
   end function io_has

   !> field_io_t's real array added later: the dataset /state/NAME (array_reals), read back
   !> only where the checkpoint has it.
   subroutine io_later_reals(io, name, a)
      class(ck_file_t), intent(inout) :: io   !! the checkpoint file and its checksum
      character(len=*), intent(in) :: name   !! field name
      real(wp), allocatable, intent(inout) :: a(:)   !! the array
      if (io%writing .or. h5_has_attr(io%h5, '/state', name // ':size')) then
         call array_reals(io, io%writing, name, a)
      end if
   end subroutine io_later_reals

   !> An array of /state: the dataset /state/NAME with the attributes NAME:lbound and
   !> NAME:size of /state (an unallocated array is not written; read back, a missing or
   !> inconsistent one is an error in h5%error). Integers come back through float64 (HDF5
   !> converts; exact below 2^53), logicals as 0/1. raw: not counted in the checksum (the
   !> integer reader counts the integers).
   subroutine array_reals(ck, writing, name, a, raw)
      type(ck_file_t), intent(inout) :: ck   !! the checkpoint file and its checksum
      logical, intent(in) :: writing       !! write (else read back)
      character(len=*), intent(in) :: name   !! field name
      real(wp), allocatable, intent(inout) :: a(:)   !! the array
      logical, intent(in), optional :: raw   !! leave the checksum alone
      real(wp), allocatable :: v(:)
      integer :: lb, n, k
      logical :: count_it
      count_it = .true.
      if (present(raw)) count_it = .not. raw
      if (writing) then
         if (.not. allocated(a)) return
         call h5_attr(ck%h5, '/state', name // ':lbound', lbound(a, 1))
         call h5_attr(ck%h5, '/state', name // ':size', size(a))
         if (size(a) > 0) call h5_write(ck%h5, '/state/' // name, a, '-')
      else
         if (allocated(a)) deallocate(a)
         n = -1
         call h5_get_attr(ck%h5, '/state', name // ':lbound', lb)
         call h5_get_attr(ck%h5, '/state', name // ':size', n)
         if (allocated(ck%h5%error)) n = -1
         if (n < 0) return
         if (lb < 0 .or. lb > 1) then
            ck%h5%error = '/state/' // name // ' starts at index ' // itoa(lb) // ' (0 or 1)'
            return
         end if
         if (n > 0) call h5_get(ck%h5, '/state/' // name, v)
         if (.not. allocated(v)) allocate(v(0))
         if (size(v) /= n) then
            if (.not. allocated(ck%h5%error)) ck%h5%error = '/state/' // name // ' holds ' // &
               itoa(size(v)) // ' values, its :size attribute says ' // itoa(n)
            return
         end if
         allocate(a(lb:lb + n - 1), source=v)
      end if
      if (.not. count_it) return
      call mix(ck%fields, int(lbound(a, 1), int64))
      call mix(ck%fields, int(size(a), int64))
      do k = lbound(a, 1), ubound(a, 1)
         call mix(ck%fields, transfer(a(k), 0_int64))
      end do
   end subroutine array_reals

   !> An integer array of /state (see array_reals).
   subroutine array_ints(ck, writing, name, a)
      type(ck_file_t), intent(inout) :: ck   !! the checkpoint file and its checksum
      logical, intent(in) :: writing       !! write (else read back)
      character(len=*), intent(in) :: name   !! field name
      integer, allocatable, intent(inout) :: a(:)   !! the array
      integer :: lb, n, k
      real(wp), allocatable :: v(:)
      if (writing) then
         if (.not. allocated(a)) return
         lb = lbound(a, 1)
         n = size(a)
         call h5_attr(ck%h5, '/state', name // ':lbound', lb)
         call h5_attr(ck%h5, '/state', name // ':size', n)
         if (n > 0) call h5_write(ck%h5, '/state/' // name, a, '-')
      else
         if (allocated(a)) deallocate(a)
         call array_reals(ck, .false., name, v, raw=.true.)
         if (.not. allocated(v)) return
         if (any(ieee_is_nan(v))) then
            ck%h5%error = '/state/' // name // ' holds a value that is not a number'
            return
         else if (any(abs(v) > real(huge(1), wp))) then
            ck%h5%error = '/state/' // name // ' holds a value beyond the integers'
            return
         else if (any(abs(v - anint(v)) > 0.0_wp)) then
            ck%h5%error = '/state/' // name // ' holds a value that is not a whole number'
            return
         end if
         allocate(a(lbound(v, 1):ubound(v, 1)), source=nint(v))
      end if
      call mix(ck%fields, int(lbound(a, 1), int64))
      call mix(ck%fields, int(size(a), int64))
      do k = lbound(a, 1), ubound(a, 1)
         call mix(ck%fields, int(a(k), int64))
      end do
   end subroutine array_ints

   !> Count a value (its 64 bits) in a checksum: its four 16-bit pieces, low first.
   pure subroutine mix(f, bits)
      type(fletcher_t), intent(inout) :: f   !! the checksum
      integer(int64), intent(in) :: bits     !! the value's bits
      integer :: k
      do k = 0, 3
         f%sum1 = mod(f%sum1 + ibits(bits, 16 * k, 16), fletcher_prime)
         f%sum2 = mod(f%sum2 + f%sum1, fletcher_prime)
      end do
   end subroutine mix

   !> Count a string in a checksum: its length, then each character.
   pure subroutine mix_text(f, text)
      type(fletcher_t), intent(inout) :: f   !! the checksum
      character(len=*), intent(in) :: text   !! the string (as read back: no trailing blanks)
      integer :: k
      call mix(f, int(len(text), int64))
      do k = 1, len(text)
         call mix(f, int(ichar(text(k:k)), int64))
      end do
   end subroutine mix_text

   !> Count a real array in a checksum: its size, then each value's bits.
   pure subroutine mix_reals(f, a)
      type(fletcher_t), intent(inout) :: f   !! the checksum
      real(wp), intent(in) :: a(:)           !! the values
      integer :: k
      call mix(f, int(size(a), int64))
      do k = 1, size(a)
         call mix(f, transfer(a(k), 0_int64))
      end do
   end subroutine mix_reals

   !> The checksum of a checkpoint of format version as hexadecimal digits (sum2, then sum1):
   !> 3, the field lists' 16 then the rest's 16; 2, the field lists' only.
   pure function checksum_text(ck, version) result(text)
      type(ck_file_t), intent(in) :: ck   !! the checkpoint file and its checksum
      integer, intent(in) :: version      !! its format: 2 or 3
      character(len=:), allocatable :: text
      character(len=32) :: hex
      write(hex, '(4z8.8)') ck%fields%sum2, ck%fields%sum1, ck%rest%sum2, ck%rest%sum1
      text = hex(1:merge(32, 16, version >= 3))
   end function checksum_text

   !> A logical array of /state as 0/1 (see array_reals).
   subroutine array_logicals(ck, writing, name, a)
      type(ck_file_t), intent(inout) :: ck   !! the checkpoint file and its checksum
      logical, intent(in) :: writing       !! write (else read back)
      character(len=*), intent(in) :: name   !! field name
      logical, allocatable, intent(inout) :: a(:)   !! the array
      integer, allocatable :: v(:)
      if (writing) then
         if (.not. allocated(a)) return
         allocate(v(lbound(a, 1):ubound(a, 1)), source=merge(1, 0, a))
         call array_ints(ck, .true., name, v)
         return
      end if
      if (allocated(a)) deallocate(a)
      call array_ints(ck, .false., name, v)
      if (allocated(v)) allocate(a(lbound(v, 1):ubound(v, 1)), source=v /= 0)
   end subroutine array_logicals

   !> Read a checkpoint for the run set up from deck (mesh, load) and check that the
   !> restart can be identical to an uninterrupted run; every refusal is exit status 2.
   !> Everything is read first and the checksum compared before any value is used; then
   !> every count, index and list is range-checked (format 2, read under
   !> --restart-any-version, sums fewer values: the range checks still hold).
   subroutine read_checkpoint(path, rec, mesh, load, ck, err, any_version)
      character(len=*), intent(in) :: path   !! checkpoint file
      type(deck_record_t), intent(in) :: rec   !! the deck's record
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(load_t), intent(in) :: load     !! the end load
      type(checkpoint_t), intent(out) :: ck   !! the checkpoint read
      type(spb_error_t), allocatable, intent(out) :: err   !! the error (allocated: it failed)
      logical, intent(in), optional :: any_version   !! accept another program's (ck%program)
      type(ck_file_t) :: cf
      character(len=:), allocatable :: text, why
      real(wp), allocatable :: times(:)
      integer :: version
      logical :: exists, accept_any
      accept_any = .false.
      if (present(any_version)) accept_any = any_version
      inquire(file=path, exist=exists)
      if (.not. exists) then
         call make_error(err, '--restart: ''' // path // ''' does not exist')
         return
      end if
      call h5_open_read(cf%h5, path)
      if (allocated(cf%h5%error)) then
         call make_error(err, '--restart: ''' // path // ''' is not an HDF5 file (' // &
                         cf%h5%error // ')')
         return
      end if
      call h5_get_attr(cf%h5, '/', 'format', text)
      version = format_version(text)
      if (version == 1) then
         call refuse('is in the format ''' // format_1 // ''', which has no checksum and ' // &
                     'is no longer read: run the deck from its start (doc/migration.md)')
         return
      else if (version == 0 .or. allocated(cf%h5%error)) then
         call refuse('is not a spallbar checkpoint (no root attribute format = ''' // &
                     format_name // ''')')
         return
      end if
      call h5_get_attr(cf%h5, '/identity', 'program', text)
      if (allocated(cf%h5%error)) then
         call refuse('is damaged: it does not name the program that wrote it (/identity program)')
         return
      end if
      call mix_text(cf%rest, text)
      ck%program = text
      if (text /= program_identity() .and. .not. accept_any) then
         call refuse('was written by ' // text // ', this is ' // program_identity() // &
                     ': a restart continues the run of the program that wrote it ' // &
                     '(--restart-any-version accepts it, and every output then says so)')
         return
      else if (text == program_identity() .and. version /= 3) then
         call refuse('is damaged: it names this program, which writes ''' // format_name // &
                     ''', and says format ' // itoa(version))
         return
      end if
      ! the git revision came with format 3 (a format 2 checkpoint has none)
      if (version >= 3) then
         call h5_get_attr(cf%h5, '/identity', 'revision', text)
         call mix_text(cf%rest, text)
      end if
      why = identity_problem(cf, rec, mesh, load)
      if (len(why) > 0) then
         call refuse(why)
         return
      end if
      ! everything else, unused until the checksum is compared
      ! what the ends are is the mesh's (the deck's); the checkpoint holds what they keep
      call define_ends(ck%st%ends, mesh)
      call state_fields(cf, ck%st, .false.)
      call read_profile_times(cf, times)
      call summary_fields(ck%summary, cf, '/run')
      call read_marks(cf, ck%marks, rec)
      if (allocated(cf%h5%error)) then
         call refuse('cannot be read: ' // cf%h5%error)
         return
      end if
      call h5_get_attr(cf%h5, '/', 'checksum', text)
      if (text /= checksum_text(cf, version)) then
         why = 'its state, summary and output counts'
         if (version >= 3) why = 'what a restart reads'
         call refuse('is damaged: the checksum of ' // why // ' is ' // &
                     checksum_text(cf, version) // ', it was written as ' // text)
         return
      end if
      why = state_problem(ck%st, mesh%n)
      if (len(why) == 0) why = list_problem(ck%st, mesh%n)
      if (len(why) == 0) why = marks_problem(ck%marks, text_count(rec))
      if (len(why) == 0) why = summary_problem(ck%summary)
      if (len(why) == 0) why = diag_problem(ck%summary%diag, mesh%n)
      if (len(why) == 0 .and. .not. all(ieee_is_finite(times))) then
         why = 'is damaged: /identity/profile_times holds a value that is not finite'
      else if (len(why) == 0 .and. any(abs(times) > 1.0e60_wp)) then
         why = 'is damaged: /identity/profile_times holds ' // rtoa(maxval(abs(times)))
      end if
      if (len(why) > 0) then
         call refuse(why)
         return
      end if
      if (ck%st%step > mesh%nsteps) then
         call refuse('is at step ' // itoa(ck%st%step) // ' (t = ' // &
                     rtoa(real(ck%st%step, wp) * mesh%dt) // ' s), after this deck''s t_end = ' // &
                     rtoa(rec%t_end) // ' s (' // itoa(mesh%nsteps) // ' steps)')
         return
      end if
      ! profile times up to the checkpoint are in the outputs already: they must not change
      if (.not. same(pack(times, up_to(times, mesh%dt, ck%st%step)), &
                     pack(rec%profile_times, up_to(rec%profile_times, mesh%dt, ck%st%step)))) then
         call refuse('has other profile_times up to its t = ' // &
                     rtoa(real(ck%st%step, wp) * mesh%dt) // ' s than &run profile_times here')
         return
      end if
      call h5_close(cf%h5)
   contains
      !> Refuse the checkpoint (exit 2) with the reason, and close it.
      subroutine refuse(why)
         character(len=*), intent(in) :: why   !! the reason, after the checkpoint's path
         call make_error(err, '--restart: ''' // path // ''' ' // why, code=exit_input)
         call h5_close(cf%h5)
      end subroutine refuse
   end subroutine read_checkpoint

   !> The version of a checkpoint's root attribute format (3, 2 or 1; 0: not a checkpoint).
   pure integer function format_version(text)
      character(len=*), intent(in) :: text   !! the attribute's value
      select case (text)
      case (format_name)
         format_version = 3
      case (format_2)
         format_version = 2
      case (format_1)
         format_version = 1
      case default
         format_version = 0
      end select
   end function format_version

   !> The profile times of the checkpoint's run (/identity n_profiles and profile_times),
   !> counted in the rest of the checksum; a count that does not match them is an error in
   !> ck%h5%error.
   subroutine read_profile_times(ck, times)
      type(ck_file_t), intent(inout) :: ck   !! the checkpoint file and its checksum
      real(wp), allocatable, intent(out) :: times(:)   !! the times [s]
      integer :: n
      call h5_get_attr(ck%h5, '/identity', 'n_profiles', n)
      call mix(ck%rest, int(n, int64))
      if (n > 0) then
         call h5_get(ck%h5, '/identity/profile_times', times)
      end if
      if (.not. allocated(times)) allocate(times(0))
      if (size(times) /= max(n, 0) .or. n < 0) then
         if (.not. allocated(ck%h5%error)) ck%h5%error = '/identity n_profiles = ' // &
            itoa(n) // ' with ' // itoa(size(times)) // ' profile_times'
         return
      end if
      if (n > 0) call mix_reals(ck%rest, times)
   end subroutine read_profile_times

   !> Which of times (s) fall on a step up to step (the nearest step to each, as the run
   !> takes them); computed in reals, so a damaged time cannot overflow an integer.
   pure function up_to(times, dt, step) result(mask)
      real(wp), intent(in) :: times(:)   !! the times [s], finite
      real(wp), intent(in) :: dt         !! the step [s]
      integer, intent(in) :: step        !! the last step
      logical :: mask(size(times))
      mask = anint(times / dt) <= real(step, wp)
   end function up_to

   !> Why a state read back cannot be the state of a mesh of n cells ('' when it can): every
   !> array allocated with the bounds init_state gives it, every count within its list.
   function state_problem(st, n) result(why)
      type(state_t), intent(in) :: st   !! the state read back
      integer, intent(in) :: n          !! cells of the mesh
      character(len=:), allocatable :: why
      why = ''
      if (.not. allocated(st%ua)) then
         why = 'has no state'
      else if (lbound(st%ua, 1) /= 0 .or. ubound(st%ua, 1) /= n) then
         why = 'holds a state of ' // itoa(size(st%ua) - 1) // ' cells, the mesh has ' // itoa(n)
      else if (.not. (bounds_are(st%ub, 0, n) .and. bounds_are(st%dua, 0, n) .and. &
               bounds_are(st%dub, 0, n) .and. bounds_are(st%s, 0, n + 1) .and. &
               bounds_are(st%s_old, 0, n + 1) .and. bounds_are(st%section, 0, n) .and. &
               bounds_are(st%strength, 0, n) .and. bounds_are(st%cell_strength, 1, n))) then
         why = 'is damaged: a state array has other bounds than the mesh gives'
      else if (.not. (allocated(st%joined) .and. allocated(st%cracked) .and. &
               allocated(st%fm%is_cut) .and. allocated(st%gen%frag_id) .and. &
               allocated(st%gen%frag_parent) .and. allocated(st%gen%frag_birth))) then
         why = 'is damaged: a list of its state is missing'
      else if (any([lbound(st%joined, 1), ubound(st%joined, 1), lbound(st%cracked, 1), &
               ubound(st%cracked, 1), lbound(st%fm%is_cut, 1), ubound(st%fm%is_cut, 1), &
               lbound(st%gen%frag_id, 1), ubound(st%gen%frag_id, 1), &
               lbound(st%gen%frag_parent, 1), ubound(st%gen%frag_parent, 1), &
               lbound(st%gen%frag_birth, 1), ubound(st%gen%frag_birth, 1)] /= &
               [0, n, 0, n, 1, n, 0, n, 0, n, 0, n])) then
         why = 'is damaged: a state list has other bounds than the mesh gives'
      else if (.not. (all(ieee_is_finite(st%ua)) .and. all(ieee_is_finite(st%ub)) .and. &
               all(ieee_is_finite(st%dua)) .and. all(ieee_is_finite(st%dub)) .and. &
               all(ieee_is_finite(st%s)) .and. all(ieee_is_finite(st%s_old)) .and. &
               all(ieee_is_finite(st%section)))) then
         why = 'is damaged: a displacement or stress of its state is not finite'
      else if (st%step < 0 .or. st%n_split < 0 .or. st%n_skip < 0 .or. st%fm%n_cut < 0 .or. &
               st%gen%n_frag_ids < 1 .or. st%n_breakable < 0 .or. st%n_breakable > n .or. &
               st%ring_next < 0 .or. st%ring_wait < 0) then
         why = 'is damaged: a count of its state is out of range'
      else if (st%coh%on .and. .not. (bounds_are(st%coh%gc, 0, n) .and. &
               bounds_are(st%coh%r, 0, n) .and. bounds_are(st%coh%dc, 0, n) .and. &
               bounds_are(st%coh%dmax, 0, n) .and. bounds_are(st%coh%q, 0, n) .and. &
               bounds_are(st%coh%opening, 0, n) .and. allocated(st%coh%active))) then
         why = 'is damaged: a cohesive crack array has other bounds than the mesh gives'
      else if (st%dmg%on .and. .not. (bounds_are(st%dmg%k, 0, n) .and. &
               bounds_are(st%dmg%lambda, 0, n) .and. bounds_are(st%dmg%d, 0, n))) then
         why = 'is damaged: a damage array has other bounds than the mesh gives'
      else if (.not. damage_fits(st%dmg)) then
         why = 'is damaged: a damage integral, exponent or damage of its state is out of range'
      else if (.not. (allocated(st%split) .and. allocated(st%skip_test) .and. &
                      allocated(st%fm%cut))) then
         why = 'is damaged: a list of its state is missing'
      else if (st%n_split > min(size(st%split), max(n - 1, 0)) .or. &
               size(st%split) < max(1, n - 1) .or. &
               st%n_skip > size(st%skip_test) .or. st%fm%n_cut > min(size(st%fm%cut), n)) then
         why = 'is damaged: a count of its state exceeds its list'
      end if
   end function state_problem

   !> Why the lists of a state whose bounds and counts fit (state_problem) cannot be used
   !> ('' when they can): the split nodes ascending within 1..n-1, exactly the interior
   !> nodes not joined; the cut cells within 1..n, exactly those is_cut marks; the nodes
   !> joined this step within 0..n; fragment ids within those issued, births not after the
   !> step; the active cohesive cracks as many as counted.
   function list_problem(st, n) result(why)
      type(state_t), intent(in) :: st   !! the state read back (state_problem: '')
      integer, intent(in) :: n          !! cells of the mesh
      character(len=:), allocatable :: why
      integer :: c
      why = ''
      associate (split => st%split(1:st%n_split), cut => st%fm%cut(1:st%fm%n_cut))
      if (any(split < 1 .or. split > n - 1)) then
         why = 'is damaged: /state/split names a node outside 1..' // itoa(n - 1)
         return
      end if
      do c = 2, size(split)
         if (split(c) <= split(c - 1)) then
            why = 'is damaged: /state/split is not in ascending order'
            return
         end if
      end do
      if (st%n_split /= count(.not. st%joined(1:n - 1)) .or. any(st%joined(split))) then
         why = 'is damaged: /state/split is not the list of the split nodes of /state/joined'
      else if (any(cut < 1 .or. cut > n)) then
         why = 'is damaged: /state/cut names a cell outside 1..' // itoa(n)
      else if (st%fm%n_cut /= count(st%fm%is_cut)) then
         why = 'is damaged: /state/cut is not the list of the cells /state/is_cut marks'
      else if (.not. all(st%fm%is_cut(cut))) then
         why = 'is damaged: /state/cut is not the list of the cells /state/is_cut marks'
      else if (any(st%skip_test(1:st%n_skip) < 0 .or. st%skip_test(1:st%n_skip) > n)) then
         why = 'is damaged: /state/skip_test names a node outside 0..' // itoa(n)
      else if (any(st%gen%frag_id < 0 .or. st%gen%frag_id > st%gen%n_frag_ids .or. &
                   st%gen%frag_parent < 0 .or. st%gen%frag_parent > st%gen%n_frag_ids)) then
         why = 'is damaged: a fragment id of its state is beyond the ' // &
               itoa(st%gen%n_frag_ids) // ' issued'
      else if (any(st%gen%frag_birth < 0 .or. st%gen%frag_birth > st%step)) then
         why = 'is damaged: a fragment of its state is born after its step'
      else if (st%coh%on) then
         if (lbound(st%coh%active, 1) /= 0 .or. ubound(st%coh%active, 1) /= n) then
            why = 'is damaged: /state/coh_active has other bounds than the mesh gives'
         else if (st%coh%n_active /= count(st%coh%active)) then
            why = 'is damaged: coh_n_active is not the number of active cohesive cracks'
         end if
      end if
      end associate
   end function list_problem

   !> Whether the damage read back (bounds checked) holds values a run can have: K >= 0,
   !> lambda > 0 and finite, D/K >= 0 and finite (true without damage).
   pure logical function damage_fits(dmg)
      type(damage_t), intent(in) :: dmg   !! the damage read back
      damage_fits = .true.
      if (.not. dmg%on) return
      damage_fits = all(ieee_is_finite(dmg%k)) .and. all(ieee_is_finite(dmg%lambda)) .and. &
                    all(ieee_is_finite(dmg%d)) .and. all(dmg%k >= 0.0_wp) .and. &
                    all(dmg%lambda > 0.0_wp) .and. all(dmg%d >= 0.0_wp)
   end function damage_fits

   !> Whether a is allocated with bounds lo:hi.
   pure logical function bounds_are(a, lo, hi)
      real(wp), allocatable, intent(in) :: a(:)   !! a state array
      integer, intent(in) :: lo                   !! its lower bound
      integer, intent(in) :: hi                   !! its upper bound
      bounds_are = allocated(a)
      if (bounds_are) bounds_are = lbound(a, 1) == lo .and. ubound(a, 1) == hi
   end function bounds_are

   !> Why the checkpoint's identity does not fit this run ('' when it does): the deck, the
   !> mesh, a load table; each value read is counted in the rest of the checksum.
   function identity_problem(ck, rec, mesh, load) result(why)
      type(ck_file_t), intent(inout) :: ck   !! the checkpoint file and its checksum
      type(deck_record_t), intent(in) :: rec   !! the deck's record
      type(mesh_t), intent(in) :: mesh     !! the mesh
      type(load_t), intent(in) :: load     !! the end load
      character(len=:), allocatable :: why
      character(len=:), allocatable :: text, here
      real(wp) :: x
      real(wp), allocatable :: tab(:)
      integer :: i
      why = ''
      ! the deck
      call h5_get_attr(ck%h5, '/identity', 'deck', text)
      call mix_text(ck%rest, text)
      here = deck_identity(rec)
      if (text /= here) then
         why = ('was written for another deck: ' // first_difference(text, here) // &
                     ' (only title, t_end, checkpoint, checkpoint_every and later ' // &
                     'profile_times may change)')
         return
      end if
      call h5_get_attr(ck%h5, '/identity', 'dt', x)
      call mix(ck%rest, transfer(x, 0_int64))
      call h5_get_attr(ck%h5, '/identity', 'cells', i)
      call mix(ck%rest, int(i, int64))
      if (.not. same([x], [mesh%dt]) .or. i /= mesh%n) then
         why = ('has dt = ' // rtoa(x) // ' s and ' // itoa(i) // ' cells, this ' // &
                     'deck''s mesh dt = ' // rtoa(mesh%dt) // ' s and ' // itoa(mesh%n) // ' cells')
         return
      end if
      if (load%kind == load_table) then
         call h5_get(ck%h5, '/identity/load_t', tab)
         if (.not. allocated(tab)) allocate(tab(0))
         call mix_reals(ck%rest, tab)
         if (.not. same(tab, load%t)) then
            why = ('was written with another &load table (its times differ from ''' // &
                        rec%table // ''')')
            return
         end if
         call h5_get(ck%h5, '/identity/load_p', tab)
         if (.not. allocated(tab)) allocate(tab(0))
         call mix_reals(ck%rest, tab)
         if (.not. same(tab, load%p)) then
            why = ('was written with another &load table (its pressures differ from ''' &
                        // rec%table // ''')')
            return
         end if
      end if
   end function identity_problem

   !> The marks of the outputs, counted in the checksum (the text files' in the rest, the
   !> counts in the fields); a byte count that is not a whole number in 0..2^53 comes back
   !> as -1 (marks_problem refuses it).
   subroutine read_marks(ck, marks, rec)
      type(ck_file_t), intent(inout) :: ck   !! the checkpoint file and its checksum
      type(output_marks_t), intent(inout) :: marks   !! how far the outputs reach
      type(deck_record_t), intent(in) :: rec   !! the deck's record (its gauges)
      character(len=:), allocatable :: text
      real(wp) :: x
      integer :: k
      do k = 1, text_count(rec)
         call h5_get_attr(ck%h5, '/outputs', 'body' // text_extensions(k), x)
         call mix(ck%rest, transfer(x, 0_int64))
         marks%body(k) = -1
         if (ieee_is_finite(x)) then
            if (x >= 0.0_wp .and. x <= 2.0_wp**53 .and. .not. abs(x - anint(x)) > 0.0_wp) then
               marks%body(k) = int(x, kind(marks%body))
            end if
         end if
         call h5_get_attr(ck%h5, '/outputs', 'tail_bytes' // text_extensions(k), marks%tail_n(k))
         call mix(ck%rest, int(marks%tail_n(k), int64))
         call h5_get_attr(ck%h5, '/outputs', 'tail' // text_extensions(k), text)
         call mix_text(ck%rest, text)
         ! a string attribute comes back without trailing blanks: padded to its length
         marks%tail(k) = text
         if (len(text) > tail_len) marks%tail_n(k) = -2   ! longer than any tail: refused
      end do
      call count_fields(ck, marks, .false., size(rec%gauge_x) > 0)
   end subroutine read_marks

   !> Why the marks of nt text files and the PREFIX.h5 counts cannot be used ('' when they
   !> can): byte counts whole and not negative, each tail within its body and tail_len
   !> (-1: the writer could not read it, refused by the restart naming the file).
   function marks_problem(marks, nt) result(why)
      type(output_marks_t), intent(in) :: marks   !! how far the outputs reach
      integer, intent(in) :: nt                   !! text files of the run (text_count)
      character(len=:), allocatable :: why
      integer :: k
      why = ''
      if (min(marks%rows_his, marks%rows_evt, marks%rows_imp, marks%rows_xt, marks%n_prof, &
              marks%n_frg, marks%rows_gau) < 0) then
         why = 'is damaged: a count of its outputs is negative'
         return
      end if
      do k = 1, nt
         if (marks%body(k) < 0) then
            why = 'is damaged: /outputs body' // text_extensions(k) // ' is not a byte count'
         else if (marks%tail_n(k) < -1 .or. marks%tail_n(k) > min(int(tail_len, int64), &
                  marks%body(k))) then
            why = 'is damaged: /outputs tail_bytes' // text_extensions(k) // ' = ' // &
                  itoa(marks%tail_n(k)) // ' (at most ' // itoa(tail_len) // &
                  ' and the body''s bytes)'
         else if (len_trim(marks%tail(k)) > max(marks%tail_n(k), 0)) then
            why = 'is damaged: /outputs tail' // text_extensions(k) // ' is longer than ' // &
                  'its tail_bytes'
         end if
         if (len(why) > 0) return
      end do
   end function marks_problem

   !> The one list of the outputs' row and block counts a checkpoint keeps (attributes of
   !> /outputs), written or read back; rows_gauges only by a run with gauges.
   subroutine count_fields(ck, marks, writing, gauges)
      type(ck_file_t), intent(inout) :: ck   !! the checkpoint file and its checksum
      type(output_marks_t), intent(inout) :: marks   !! how far the outputs reach
      logical, intent(in) :: writing           !! write (else read back)
      logical, intent(in) :: gauges            !! the run has gauges (PREFIX.gau, /gauges)
      call field(ck, writing, '/outputs', 'rows_history', marks%rows_his)
      call field(ck, writing, '/outputs', 'rows_events', marks%rows_evt)
      call field(ck, writing, '/outputs', 'rows_impacts', marks%rows_imp)
      call field(ck, writing, '/outputs', 'rows_xt', marks%rows_xt)
      call field(ck, writing, '/outputs', 'profiles', marks%n_prof)
      call field(ck, writing, '/outputs', 'fragment_blocks', marks%n_frg)
      if (gauges) call field(ck, writing, '/outputs', 'rows_gauges', marks%rows_gau)
   end subroutine count_fields


   !> The deck values a restart must not change: 'group name = value' lines of the echo,
   !> without title, t_end, checkpoint, checkpoint_every and profile_times (checked apart).
   function deck_identity(rec) result(text)
      type(deck_record_t), intent(in) :: rec   !! the deck's record
      character(len=:), allocatable :: text
      integer :: k
      text = ''
      associate (items => rec%items)
      do k = 1, size(items)
         if (items(k)%group == 'run') then
            select case (items(k)%name)
            case ('title', 't_end', 'checkpoint', 'checkpoint_every', 'profile_times', 'header')
               cycle
            case default
               ! every other value identifies the run
            end select
         end if
         ! a variable added since checkpoints were first written, left at its default, is
         ! what a checkpoint made before it had: such checkpoints still restart
         if (.not. items(k)%given .and. any(later_variables == items(k)%group // ':' // &
                                             items(k)%name)) cycle
         text = text // '&' // items(k)%group // ' ' // items(k)%name // ' = ' // &
                items(k)%value // nl
      end do
      end associate
   end function deck_identity

   !> The first line of a that differs from b, for a message.
   function first_difference(a, b) result(msg)
      character(len=*), intent(in) :: a    !! one text, lines ended by nl (the checkpoint's)
      character(len=*), intent(in) :: b    !! the other text (this run's)
      character(len=:), allocatable :: msg
      integer :: i, ia, ib
      i = 1
      do while (i <= min(len(a), len(b)))
         if (a(i:i) /= b(i:i)) exit
         i = i + 1
      end do
      ia = index(a(:i - 1), nl, back=.true.) + 1
      ib = index(a(i:), nl)
      if (ib == 0) then
         msg = a(ia:)
      else
         msg = a(ia:i + ib - 2)
      end if
      ib = index(b(i:), nl)
      if (ib == 0) then
         msg = 'there ' // msg // ', here ' // b(ia:)
      else
         msg = 'there ' // msg // ', here ' // b(ia:i + ib - 2)
      end if
   end function first_difference

   !> Two arrays equal bit for bit (and in size).
   pure logical function same(a, b)
      real(wp), intent(in) :: a(:)         !! one array
      real(wp), intent(in) :: b(:)         !! the other array
      same = size(a) == size(b)
      if (same) same = all(transfer(a, 0_int64, size(a)) == transfer(b, 0_int64, size(b)))
   end function same
end module spb_checkpoint
