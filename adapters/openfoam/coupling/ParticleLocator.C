#include "ParticleLocator.H"

Foam::cosim::ParticleLocator::ParticleLocator(const polyMesh& mesh)
:
    mesh_(mesh),
    // This processor's own box: mesh.bounds() is the whole mesh's on every processor, which
    // sent every parcel of the others into the octree search
    bounds_(boundBox(mesh.points(), false)),
    maxSteps_(max(label(100), label(4*Foam::cbrt(scalar(mesh.nCells())))))
{
    // Small tolerance so points on the outer faces are not dropped by the box test
    bounds_.inflate(1e-9);

    // Build the demand-driven search structures now: search() runs on several threads
    (void)mesh.cellTree();
    (void)mesh.tetBasePtIs();

    const cellList& cells = mesh.cells();
    const vectorField& Cf = mesh.faceCentres();
    const vectorField& Sf = mesh.faceAreas();
    const labelList& own = mesh.faceOwner();
    const labelList& nei = mesh.faceNeighbour();
    faceStart_.setSize(cells.size() + 1);
    label n = 0;
    forAll(cells, c)
    {
        faceStart_[c] = n;
        n += cells[c].size();
    }
    faceStart_[cells.size()] = n;
    faceCentre_.setSize(n);
    faceOut_.setSize(n);
    faceArea_.setSize(n);
    across_.setSize(n);
    forAll(cells, c)
    {
        label k = faceStart_[c];
        for (const label facei : cells[c])
        {
            const bool owned = (own[facei] == c);
            faceCentre_[k] = Cf[facei];
            faceOut_[k] = owned ? Sf[facei] : -Sf[facei];
            faceArea_[k] = mag(Sf[facei]);
            across_[k] =
                mesh.isInternalFace(facei) ? (owned ? nei[facei] : own[facei]) : -1;
            ++k;
        }
    }
}


bool Foam::cosim::ParticleLocator::inside(const point& p, label c) const
{
    for (label k = faceStart_[c]; k < faceStart_[c + 1]; ++k)
    {
        const vector proj = p - faceCentre_[k];
        if ((faceOut_[k] & proj) > 0)
        {
            return false;
        }
    }
    return true;
}


Foam::label Foam::cosim::ParticleLocator::reachedFaces
(
    const point& p,
    scalar radius,
    label c,
    label* slots,
    label room
) const
{
    const scalar reach = radius + 1e-12;
    label n = 0;
    for (label k = faceStart_[c]; k < faceStart_[c + 1]; ++k)
    {
        if ((faceOut_[k] & (p - faceCentre_[k])) + reach*faceArea_[k] > 0)
        {
            if (n == room)
            {
                return -1;
            }
            slots[n++] = k;
        }
    }
    return n;
}


Foam::label Foam::cosim::ParticleLocator::firstBeyond
(
    const point& q,
    const label* slots,
    label n
) const
{
    for (label i = 0; i < n; ++i)
    {
        const label k = slots[i];
        if ((faceOut_[k] & (q - faceCentre_[k])) > 0)
        {
            return k;
        }
    }
    return -1;
}


bool Foam::cosim::ParticleLocator::inBox
(
    const treeBoundBox& box,
    const point& p,
    scalar margin
)
{
    const point& lo = box.min();
    const point& hi = box.max();
    return
        p.x() >= lo.x() - margin && p.x() <= hi.x() + margin
     && p.y() >= lo.y() - margin && p.y() <= hi.y() + margin
     && p.z() >= lo.z() - margin && p.z() <= hi.z() + margin;
}


Foam::label Foam::cosim::ParticleLocator::search(const point& p) const
{
    if (!inBounds(p))
    {
        return -1;
    }
    return mesh_.findCell(p);
}


Foam::label Foam::cosim::ParticleLocator::walk(const point& p, label celli) const
{
    const vectorField& Cc = mesh_.cellCentres();

    for (label step = 0; step < maxSteps_; ++step)
    {
        if (inside(p, celli))
        {
            return celli;
        }

        // Leave through the face the line centre -> p crosses first
        const point& c = Cc[celli];
        const vector d = p - c;
        label exit = -1;
        scalar lambdaMin = GREAT;
        for (label k = faceStart_[celli]; k < faceStart_[celli + 1]; ++k)
        {
            const vector& n = faceOut_[k];
            const scalar along = d & n;
            if (along <= VSMALL)
            {
                continue;
            }
            const scalar lambda = ((faceCentre_[k] - c) & n)/along;
            if (lambda < lambdaMin)
            {
                lambdaMin = lambda;
                exit = k;
            }
        }
        if (exit < 0 || across_[exit] < 0)
        {
            return -1;
        }
        celli = across_[exit];
    }
    return -1;
}


Foam::label Foam::cosim::ParticleLocator::locate(const point& p, label seed) const
{
    if (seed >= 0 && seed < mesh_.nCells())
    {
        const label celli = walk(p, seed);
        if (celli >= 0)
        {
            return celli;
        }
    }
    return search(p);
}
