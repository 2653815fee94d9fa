package mcstat

// #include <mcstat.h>
import "C"

import (
	"fmt"
	"math"
	"unsafe"
)

// ---- per-pixel rows -------------------------------------------------------------

// RowFlags modify the row-wise calls.
type RowFlags uint

const (
	// NoIntervals skips critical values and confidence intervals (the
	// results' Critical and ConfInt are nil): the cheap path when only the
	// decision map is wanted.
	NoIntervals RowFlags = C.MCSTAT_ROWS_NO_INTERVALS
	// OmitNaN skips NaN values in each row (+-Inf remains an error); not
	// for the tests on accumulators.
	OmitNaN RowFlags = C.MCSTAT_ROWS_OMIT_NAN
	// PixelsRender makes Welch's and the paired per-pixel tests valid on
	// renders (constant or one-nonzero sides floored by the rule of three,
	// a numerical floor from the inputs' type, Hsu's df, deterministic
	// differences; mcstat.h, MCSTAT_PIXELS_RENDER).  Per-pixel Welch and
	// paired calls only.
	PixelsRender RowFlags = C.MCSTAT_PIXELS_RENDER
)

// Matrix is Rows rows of Cols values: row i is
// Data[i*Stride : i*Stride+Cols] (Stride 0 means Cols, rows back to back).
// An image whose every pixel holds k estimates is Rows = pixels, Cols = k.
type Matrix struct {
	Data       []float64
	Rows, Cols int
	Stride     int
}

// stride is the effective stride, after checking that every row lies in
// Data (the C library trusts its pointers: a short slice would be read past
// its end).
func (m Matrix) stride(name string) (int, error) {
	s := m.Stride
	if s == 0 {
		s = m.Cols
	}
	if m.Rows < 0 || m.Cols < 0 || s < 0 {
		return 0, invalid(name + ": negative Rows, Cols or Stride")
	}
	if m.Rows > 0 && s > 0 && m.Rows-1 > (math.MaxInt-m.Cols)/s {
		return 0, invalid(name + ": Rows * Stride overflows")
	}
	if m.Rows > 0 && (m.Rows-1)*s+m.Cols > len(m.Data) {
		return 0, invalid(fmt.Sprintf("%s: %d rows of %d values at stride %d need %d values, Data has %d",
			name, m.Rows, m.Cols, s, (m.Rows-1)*s+m.Cols, len(m.Data)))
	}
	return s, nil
}

// invalid is ErrInvalidArgument with a sentence naming the argument.
func invalid(why string) error {
	return &Error{Status: int(C.MCSTAT_EINVAL), Message: why}
}

// RowResult is one row's outcome: Result on success, else Err (matched
// with errors.Is against the Err* sentinels) and a nil Result.
type RowResult struct {
	Result *Result
	Err    error
}

// notRun marks a status the library did not write (the whole call was refused).
const notRun = -1

// runRows calls f with arrays for rows results and statuses and converts
// them.  When the library refused the call as a whole (nothing written), it
// returns nil and that error; otherwise every row's outcome and, when some
// row failed, the first failing row's error.
func runRows(rows int, f func(out *C.struct_mcstat_result, status *C.int32_t) C.int) ([]RowResult, error) {
	if rows == 0 {
		return []RowResult{}, nil
	}
	out := make([]C.struct_mcstat_result, rows)
	status := make([]C.int32_t, rows)
	for i := range status {
		status[i] = notRun
	}
	st := f(&out[0], &status[0])
	if st != C.MCSTAT_OK && status[0] == notRun {
		return nil, newError(st)
	}
	res := make([]RowResult, rows)
	for i := range res {
		if status[i] == C.MCSTAT_OK {
			res[i].Result = fromC(&out[i])
		} else {
			res[i].Err = newError(C.int(status[i]))
		}
	}
	return res, check(st)
}

func sz(n int) C.size_t { return C.size_t(n) }

// TTest1Matrix is TTest1 on every row of x: row i's result is bit for bit
// TTest1 on that row.
func TTest1Matrix(x Matrix, mu0 float64, alt Alternative, alpha float64, flags RowFlags) ([]RowResult, error) {
	s, err := x.stride("x")
	if err != nil {
		return nil, err
	}
	return runRows(x.Rows, func(o *C.struct_mcstat_result, st *C.int32_t) C.int {
		return C.mcstat_t_test_1_matrix(ptr(x.Data), sz(x.Cols), sz(s), sz(x.Rows), C.double(mu0), C.int(alt),
			C.double(alpha), C.uint(flags), o, st)
	})
}

// TTest2Matrix is TTest2 on every pair of rows of x and y (equal Rows).
func TTest2Matrix(x, y Matrix, mu0 float64, alt Alternative, alpha float64, flags RowFlags) ([]RowResult, error) {
	sx, sy, err := twoMatrices(x, y)
	if err != nil {
		return nil, err
	}
	return runRows(x.Rows, func(o *C.struct_mcstat_result, st *C.int32_t) C.int {
		return C.mcstat_t_test_2_matrix(ptr(x.Data), sz(x.Cols), sz(sx), ptr(y.Data), sz(y.Cols), sz(sy), sz(x.Rows),
			C.double(mu0), C.int(alt), C.double(alpha), C.uint(flags), o, st)
	})
}

// VarTest1Matrix is VarTest1 on every row of x.
func VarTest1Matrix(x Matrix, sigma2 float64, alt Alternative, alpha float64, flags RowFlags) ([]RowResult, error) {
	s, err := x.stride("x")
	if err != nil {
		return nil, err
	}
	return runRows(x.Rows, func(o *C.struct_mcstat_result, st *C.int32_t) C.int {
		return C.mcstat_var_test_1_matrix(ptr(x.Data), sz(x.Cols), sz(s), sz(x.Rows), C.double(sigma2), C.int(alt),
			C.double(alpha), C.uint(flags), o, st)
	})
}

// VarTest2Matrix is VarTest2 on every pair of rows of x and y (equal Rows).
func VarTest2Matrix(x, y Matrix, ratio float64, alt Alternative, alpha float64, flags RowFlags) ([]RowResult, error) {
	sx, sy, err := twoMatrices(x, y)
	if err != nil {
		return nil, err
	}
	return runRows(x.Rows, func(o *C.struct_mcstat_result, st *C.int32_t) C.int {
		return C.mcstat_var_test_2_matrix(ptr(x.Data), sz(x.Cols), sz(sx), ptr(y.Data), sz(y.Cols), sz(sy),
			sz(x.Rows), C.double(ratio), C.int(alt), C.double(alpha), C.uint(flags), o, st)
	})
}

func twoMatrices(x, y Matrix) (int, int, error) {
	if x.Rows != y.Rows {
		return 0, 0, invalid(fmt.Sprintf("x has %d rows, y %d", x.Rows, y.Rows))
	}
	sx, err := x.stride("x")
	if err != nil {
		return 0, 0, err
	}
	sy, err := y.stride("y")
	return sx, sy, err
}

// ---- arrays of accumulators -----------------------------------------------------

// MomentsRows is an array of accumulators, one per pixel: added an image
// (or a stack of images) at a time, merged element-wise, serialized, and
// tested row by row.  Adding batches A then B gives bit for bit what adding
// them to two arrays and merging the second into the first gives.
type MomentsRows struct{ raw []C.struct_mcstat_moments }

// NewMomentsRows returns rows empty accumulators.
func NewMomentsRows(rows int) (*MomentsRows, error) {
	if rows < 0 {
		return nil, invalid("rows < 0")
	}
	m := &MomentsRows{raw: make([]C.struct_mcstat_moments, rows)}
	if rows > 0 {
		if err := check(C.mcstat_moments_init_rows(&m.raw[0], sz(rows))); err != nil {
			return nil, err
		}
	}
	return m, nil
}

func (m *MomentsRows) first() *C.struct_mcstat_moments {
	if m == nil || len(m.raw) == 0 {
		return nil
	}
	return &m.raw[0]
}

// Len is the number of accumulators.
func (m *MomentsRows) Len() int {
	if m == nil {
		return 0
	}
	return len(m.raw)
}

// At returns a copy of accumulator i (nil when i is out of range).
func (m *MomentsRows) At(i int) *Moments {
	if i < 0 || i >= m.Len() {
		return nil
	}
	return &Moments{raw: m.raw[i]}
}

// Add adds row i of x to accumulator i (x.Rows must be Len()).  One image
// with one value per pixel is Cols = 1; a stack of k images stored
// pixel-major is Cols = k.  flags: OmitNaN.  A row that fails (ErrNonFinite,
// ErrTooBig) is left unchanged, the others are still added; rowErr[i] is
// row i's error (nil on success) and err the first failing row's.
func (m *MomentsRows) Add(x Matrix, flags RowFlags) (rowErr []error, err error) {
	s, err := x.stride("x")
	if err != nil {
		return nil, err
	}
	if x.Rows != m.Len() {
		return nil, invalid(fmt.Sprintf("x has %d rows, the array %d accumulators", x.Rows, m.Len()))
	}
	if x.Rows == 0 {
		return []error{}, nil
	}
	status := make([]C.int32_t, x.Rows)
	for i := range status {
		status[i] = notRun
	}
	st := C.mcstat_moments_add_rows(m.first(), sz(x.Rows), ptr(x.Data), sz(x.Cols), sz(s), C.uint(flags), &status[0])
	if st != C.MCSTAT_OK && status[0] == notRun {
		return nil, newError(st)
	}
	rowErr = make([]error, x.Rows)
	for i, v := range status {
		if v != C.MCSTAT_OK {
			rowErr[i] = newError(C.int(v))
		}
	}
	return rowErr, check(st)
}

// Merge merges other[i] into m[i] for every i (equal lengths; other may be m).
func (m *MomentsRows) Merge(other *MomentsRows) error {
	if other.Len() != m.Len() {
		return invalid(fmt.Sprintf("merging %d accumulators into %d", other.Len(), m.Len()))
	}
	if m.Len() == 0 {
		return nil
	}
	return check(C.mcstat_moments_merge_rows(m.first(), other.first(), sz(m.Len())))
}

// MarshalBinary writes the array as Len() records of 96 bytes (each
// MarshalBinary of one accumulator, in row order; no header).
func (m *MomentsRows) MarshalBinary() ([]byte, error) {
	b := make([]byte, m.Len()*int(C.mcstat_sizeof_moments_bytes()))
	if len(b) == 0 {
		return b, nil
	}
	if err := check(C.mcstat_moments_to_bytes_rows(m.first(), sz(m.Len()), (*C.uchar)(unsafe.Pointer(&b[0])),
		sz(len(b)))); err != nil {
		return nil, err
	}
	return b, nil
}

// UnmarshalBinary reads MarshalBinary's form; the number of accumulators is
// len(b) / 96 (ErrCorrupt for a length not a multiple of 96 or a damaged
// record; m unchanged).
func (m *MomentsRows) UnmarshalBinary(b []byte) error {
	if m == nil {
		return invalid("UnmarshalBinary into a nil *MomentsRows")
	}
	rec := int(C.mcstat_sizeof_moments_bytes())
	if len(b)%rec != 0 {
		return newError(C.MCSTAT_ECORRUPT)
	}
	rows := len(b) / rec
	tmp := make([]C.struct_mcstat_moments, rows)
	if rows > 0 {
		if err := check(C.mcstat_moments_from_bytes_rows((*C.uchar)(unsafe.Pointer(&b[0])), sz(len(b)), sz(rows),
			&tmp[0])); err != nil {
			return err
		}
	}
	m.raw = tmp
	return nil
}

func twoRows(x, y *MomentsRows) error {
	if x.Len() != y.Len() {
		return invalid(fmt.Sprintf("x has %d accumulators, y %d", x.Len(), y.Len()))
	}
	return nil
}

// TTest1MomentsRows (mcstat_t_test_1_moments_rows) is TTest1Moments on every accumulator of x.
func TTest1MomentsRows(x *MomentsRows, mu0 float64, alt Alternative, alpha float64, flags RowFlags) ([]RowResult, error) {
	return runRows(x.Len(), func(o *C.struct_mcstat_result, st *C.int32_t) C.int {
		return C.mcstat_t_test_1_moments_rows(x.first(), sz(x.Len()), C.double(mu0), C.int(alt), C.double(alpha),
			C.uint(flags), o, st)
	})
}

// TTest2MomentsRows (mcstat_t_test_2_moments_rows) is TTest2Moments on every pair of accumulators of x and y.
func TTest2MomentsRows(x, y *MomentsRows, mu0 float64, alt Alternative, alpha float64, flags RowFlags) ([]RowResult, error) {
	if err := twoRows(x, y); err != nil {
		return nil, err
	}
	return runRows(x.Len(), func(o *C.struct_mcstat_result, st *C.int32_t) C.int {
		return C.mcstat_t_test_2_moments_rows(x.first(), y.first(), sz(x.Len()), C.double(mu0), C.int(alt),
			C.double(alpha), C.uint(flags), o, st)
	})
}

// VarTest1MomentsRows (mcstat_var_test_1_moments_rows) is VarTest1Moments on every accumulator of x.
func VarTest1MomentsRows(x *MomentsRows, sigma2 float64, alt Alternative, alpha float64, flags RowFlags) ([]RowResult, error) {
	return runRows(x.Len(), func(o *C.struct_mcstat_result, st *C.int32_t) C.int {
		return C.mcstat_var_test_1_moments_rows(x.first(), sz(x.Len()), C.double(sigma2), C.int(alt),
			C.double(alpha), C.uint(flags), o, st)
	})
}

// VarTest2MomentsRows (mcstat_var_test_2_moments_rows) is VarTest2Moments on every pair of accumulators of x and y.
func VarTest2MomentsRows(x, y *MomentsRows, ratio float64, alt Alternative, alpha float64, flags RowFlags) ([]RowResult, error) {
	if err := twoRows(x, y); err != nil {
		return nil, err
	}
	return runRows(x.Len(), func(o *C.struct_mcstat_result, st *C.int32_t) C.int {
		return C.mcstat_var_test_2_moments_rows(x.first(), y.first(), sz(x.Len()), C.double(ratio), C.int(alt),
			C.double(alpha), C.uint(flags), o, st)
	})
}

// The names before 0.2.0, which read like the C library's deprecated
// mcstat_*_rows (matrix) calls: these are the _moments_rows ones.

// TTest1Rows is TTest1MomentsRows.
//
// Deprecated: use TTest1MomentsRows.
func TTest1Rows(x *MomentsRows, mu0 float64, alt Alternative, alpha float64, flags RowFlags) ([]RowResult, error) {
	return TTest1MomentsRows(x, mu0, alt, alpha, flags)
}

// TTest2Rows is TTest2MomentsRows.
//
// Deprecated: use TTest2MomentsRows.
func TTest2Rows(x, y *MomentsRows, mu0 float64, alt Alternative, alpha float64, flags RowFlags) ([]RowResult, error) {
	return TTest2MomentsRows(x, y, mu0, alt, alpha, flags)
}

// VarTest1Rows is VarTest1MomentsRows.
//
// Deprecated: use VarTest1MomentsRows.
func VarTest1Rows(x *MomentsRows, sigma2 float64, alt Alternative, alpha float64, flags RowFlags) ([]RowResult, error) {
	return VarTest1MomentsRows(x, sigma2, alt, alpha, flags)
}

// VarTest2Rows is VarTest2MomentsRows.
//
// Deprecated: use VarTest2MomentsRows.
func VarTest2Rows(x, y *MomentsRows, ratio float64, alt Alternative, alpha float64, flags RowFlags) ([]RowResult, error) {
	return VarTest2MomentsRows(x, y, ratio, alt, alpha, flags)
}
